#include "reference.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/util/content_hash.h"
#include "core/util/error.h"
#include "core/util/warning.h"

namespace vplgi {

std::string defaultReferenceCache()
{
    return cacheDirectory("out/reference-cache");
}

PathTracerParams::Mode parseReferenceMode(const std::string& text)
{
    if (text == "full") return PathTracerParams::Mode::Full;
    if (text == "direct") return PathTracerParams::Mode::Direct;
    if (text == "indirect") return PathTracerParams::Mode::Indirect;
    if (text == "clamped") return PathTracerParams::Mode::Clamped;
    if (text == "onebounce") return PathTracerParams::Mode::OneBounce;
    throw Error("--mode \"" + text + "\" must be full, direct, indirect, clamped or onebounce");
}

namespace {

std::string cacheKey(const ReferenceRequest& r)
{
    Hasher h;
    h.value(hashSceneContent(r.scene));
    hashCamera(h, r.camera);
    h.value(r.width);
    h.value(r.height);
    h.text(pathTracerImageKey(r.params)); // every image-changing parameter and the integrator's version
    return h.hex();
}

void printProgress(double fraction)
{
    const int width = 40;
    int filled = static_cast<int>(fraction * width + 0.5);
    std::fprintf(stderr, "\rreference [%.*s%*s] %3d%%", filled, "########################################",
                 width - filled, "", static_cast<int>(fraction * 100.0 + 0.5));
    if (fraction >= 1.0) std::fprintf(stderr, "\n");
    std::fflush(stderr);
}

std::string pixelCacheKey(const PixelReferenceRequest& r)
{
    Hasher h;
    h.text("pixels");
    h.value(hashSceneContent(r.scene));
    hashCamera(h, r.camera);
    h.value(r.width);
    h.value(r.height);
    for (const glm::ivec2& p : r.pixels) {
        h.value(p.x);
        h.value(p.y);
    }
    h.text(pathTracerImageKey(r.params));
    return h.hex();
}

// One pixel per line, "r g b" as hexadecimal floats (exact round trip). Empty when unreadable.
std::vector<glm::vec3> readPixelCache(const std::string& path, std::size_t count)
{
    std::ifstream in(path);
    std::vector<glm::vec3> values;
    std::string r, g, b;
    while (values.size() < count && in >> r >> g >> b)
        values.emplace_back(std::strtof(r.c_str(), nullptr), std::strtof(g.c_str(), nullptr),
                            std::strtof(b.c_str(), nullptr));
    if (values.size() != count) values.clear();
    return values;
}

void writePixelCache(const std::string& path, const std::vector<glm::vec3>& values)
{
    // A temporary sibling renamed into place: a cache never holds a half file.
    const std::string temporary = path + ".partial";
    bool ok = false;
    {
        std::ofstream out(temporary);
        out << std::hexfloat;
        for (const glm::vec3& v : values) out << v.r << " " << v.g << " " << v.b << "\n";
        out.close();
        ok = !out.fail();
    }
    std::error_code ec;
    if (ok) std::filesystem::rename(temporary, path, ec);
    if (!ok || ec) {
        std::filesystem::remove(temporary, ec);
        throw Error(path + ": write failed");
    }
}

} // namespace

CachedPixelReference obtainPixelReference(const PixelReferenceRequest& request)
{
    CachedPixelReference result;
    std::string cachePath;
    if (!request.cacheDirectory.empty()) {
        cachePath = request.cacheDirectory + "/" + pixelCacheKey(request) + ".pixels.txt";
        if (std::filesystem::exists(cachePath)) {
            result.radiance = readPixelCache(cachePath, request.pixels.size());
            result.fromCache = !result.radiance.empty();
            if (result.fromCache) return result;
        }
    }
    PixelReferenceResult rendered = renderReferencePixels(request.scene, request.rays, request.camera, request.width,
                                                          request.height, request.pixels, request.params);
    result.radiance = std::move(rendered.radiance);
    result.seconds = rendered.seconds;
    if (!cachePath.empty()) {
        std::filesystem::create_directories(request.cacheDirectory);
        writePixelCache(cachePath, result.radiance);
    }
    return result;
}

CachedReference obtainReference(const ReferenceRequest& request)
{
    CachedReference result;
    if (!request.cacheDirectory.empty()) {
        result.cachePath = request.cacheDirectory + "/" + cacheKey(request) + ".exr";
        if (std::filesystem::exists(result.cachePath)) {
            // A damaged entry (a disk filled up, a copy cut short) is a miss, not the end of the run.
            try {
                ImageRGBA32F cached = readImageLinear(result.cachePath);
                if (cached.width == request.width && cached.height == request.height) {
                    result.image = std::move(cached);
                    result.spp = request.params.spp;
                    result.fromCache = true;
                    return result;
                }
                warn(result.cachePath + ": cached reference is " + std::to_string(cached.width) + "x" +
                     std::to_string(cached.height) + ", not " + std::to_string(request.width) + "x" +
                     std::to_string(request.height) + ": rendering it again");
            } catch (const Error& e) {
                warn(std::string(e.what()) + " (a damaged reference cache entry: rendering it again)");
            }
        }
    }
    ProgressCallback progress;
    if (request.showProgress) progress = printProgress;
    ReferenceResult rendered =
        renderReference(request.scene, request.rays, request.camera, request.width, request.height, request.params, progress);
    result.image = std::move(rendered.image);
    result.spp = rendered.spp;
    result.seconds = rendered.seconds;
    // Only complete renders are cached: a time budget makes a partial one depend on the machine.
    if (!result.cachePath.empty() && rendered.spp == request.params.spp) {
        std::filesystem::create_directories(request.cacheDirectory);
        writeImage(result.cachePath, result.image);
    }
    return result;
}

} // namespace vplgi
