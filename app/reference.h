// Path-traced references with an on-disk cache keyed by scene content, camera, size, every
// parameter that changes the image and the path tracer's version (pathTracerImageKey), so tests
// and reports reuse references instead of re-rendering them.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/util/image_io.h"
#include "core/trace/path_tracer.h"

namespace vplgi {

struct ReferenceRequest {
    const Scene& scene;
    const RayScene& rays;
    const Camera& camera;
    int width = 0;
    int height = 0;
    PathTracerParams params;
    std::string cacheDirectory; // empty: no cache
    bool showProgress = false;  // progress bar on stderr
};

struct CachedReference {
    ImageRGBA32F image;
    int spp = 0;
    double seconds = 0.0;   // 0 when read from the cache
    bool fromCache = false;
    std::string cachePath;  // where it is (or would be) cached
};

CachedReference obtainReference(const ReferenceRequest& request);

// The reference at chosen pixels only (renderReferencePixels: bit-identical to those pixels of the
// full image), cached as a small text file keyed like the images plus the pixel list.
struct PixelReferenceRequest {
    const Scene& scene;
    const RayScene& rays;
    const Camera& camera;
    int width = 0;
    int height = 0;
    std::vector<glm::ivec2> pixels;
    PathTracerParams params;
    std::string cacheDirectory; // empty: no cache
};

struct CachedPixelReference {
    std::vector<glm::vec3> radiance; // per requested pixel
    double seconds = 0.0;            // 0 when read from the cache
    bool fromCache = false;
};

CachedPixelReference obtainPixelReference(const PixelReferenceRequest& request);

// $VPLGI_CACHE_DIR, else "out/reference-cache".
std::string defaultReferenceCache();
// "full", "direct", "indirect", "clamped", "onebounce" -> mode; throws Error otherwise.
PathTracerParams::Mode parseReferenceMode(const std::string& text);

} // namespace vplgi
