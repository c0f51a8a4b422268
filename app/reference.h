// Path-traced references with an on-disk cache keyed by scene content, camera, size, every
// parameter that changes the image and the path tracer's version (pathTracerImageKey), so tests
// and reports reuse references instead of re-rendering them.
#pragma once

#include <string>

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

// $VPLGI_CACHE_DIR, else "out/reference-cache".
std::string defaultReferenceCache();
// "full", "direct", "indirect", "clamped", "onebounce" -> mode; throws Error otherwise.
PathTracerParams::Mode parseReferenceMode(const std::string& text);

} // namespace vplgi
