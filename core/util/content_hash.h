// A 64-bit FNV-1a hash of everything in a scene that changes its images (geometry, transforms,
// materials, images, lights), used to key cached path-traced references.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace vplgi {

class Hasher {
public:
    void bytes(const void* data, std::size_t size);
    template <typename T>
    void value(const T& v) { bytes(&v, sizeof v); }
    void text(const std::string& s) { value(s.size()); bytes(s.data(), s.size()); }
    std::uint64_t digest() const { return mState; }
    std::string hex() const;

private:
    std::uint64_t mState = 0xcbf29ce484222325ull;
};

std::uint64_t hashSceneContent(const Scene& scene);

// Where content-keyed data (path-traced references, LightSkin's cache distributions) is kept between
// runs: $VPLGI_CACHE_DIR when it is set and not empty, else `fallback`.
std::string cacheDirectory(const std::string& fallback);
void hashCamera(Hasher& hasher, const Camera& camera);
// Everything about the lights that changes what they emit (type, placement, colour, intensity, cones).
void hashLights(Hasher& hasher, const std::vector<Light>& lights);
std::uint64_t hashLights(const std::vector<Light>& lights);

} // namespace vplgi
