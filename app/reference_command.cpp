// `vplgi reference`: the Embree path tracer (core/trace/path_tracer.h) from the command line.
#include <cstdio>
#include <filesystem>

#include "cli.h"
#include "commands.h"
#include "core/util/error.h"
#include "core/util/image_io.h"
#include "core/util/params.h"
#include "core/scene/scene_loader.h"
#include "reference.h"
#include "session.h"

namespace vplgi {

int runReference(const std::vector<std::string>& args)
{
    OptionParser parser("vplgi reference",
                        "Path-traces a ground-truth image (Embree, multi-threaded, deterministic for a seed and\n"
                        "any thread count) and writes linear radiance to an EXR. Modes (SMCIR Fig. 8): full,\n"
                        "direct, indirect (at least one bounce after the primary hit: what VPL methods estimate),\n"
                        "clamped (indirect with the geometry term leaving the primary hit clamped).");
    addSceneOptions(parser, "set a reference.* parameter (e.g. reference.maxDepth=3)");
    addSizeOptions(parser, "image", 640, 360);
    parser.value("mode", "M", "full, direct, indirect, clamped or onebounce", "full");
    parser.value("spp", "N", "samples per pixel", "64");
    parser.value("time-budget", "S", "stop after the pass that crosses S seconds (0 = none)", "0");
    parser.value("out", "FILE", "output .exr (linear radiance)", "out/reference.exr");
    parser.value("cache", "DIR", "reference cache directory ($VPLGI_CACHE_DIR or out/reference-cache)");
    parser.flag("no-cache", "neither read nor write the cache");
    if (!parser.parse(args)) return 0;

    const SceneOptions sceneArgs = sceneOptions(parser);
    const ImageSize size = imageSize(parser, 1, 16384);
    const std::string out = parser.get("out");
    require(isFloatImagePath(out), out + ": the reference is linear radiance: write an .exr");
    std::filesystem::path outDir = std::filesystem::path(out).parent_path();
    // The directory must exist (the default's is created) and take a file: checked before the path
    // tracing, not after it.
    if (parser.has("out") || outDir.empty() || std::filesystem::is_directory(outDir))
        checkWritableDirectory(out);
    if (parser.has("cache") && !parser.has("no-cache")) {
        std::error_code ec;
        const std::string cache = parser.get("cache");
        require(!std::filesystem::exists(cache, ec) || std::filesystem::is_directory(cache, ec),
                "--cache " + cache + ": not a directory");
    }

    PathTracerParams params;
    params.mode = parseReferenceMode(parser.get("mode"));
    params.spp = parser.getInt("spp", 1, 1 << 24);
    params.timeBudgetSeconds = parser.getFloat("time-budget", 0.0f, 1e7f);
    ParamSetter setter(sceneArgs.settings);
    params.visitParams(setter);
    setter.finish();

    SceneDescription description = loadSceneSpec(sceneArgs.sceneSpec);
    Scene& scene = description.scene;
    const Camera& camera = resolveCamera(scene, sceneArgs.camera);

    ParamDumper dumper;
    params.visitParams(dumper);
    std::printf("scene = %s\ncamera = %s\n%s", scene.source.c_str(), camera.name.c_str(), dumper.text().c_str());
    RayScene rays(scene);
    ReferenceRequest request{scene, rays, camera, size.width, size.height, params,
                             parser.has("no-cache") ? "" : (parser.has("cache") ? parser.get("cache") : defaultReferenceCache()),
                             true};
    CachedReference reference = obtainReference(request);
    if (reference.fromCache) std::printf("from cache %s\n", reference.cachePath.c_str());
    else std::printf("rendered %d spp in %.2f s\n", reference.spp, reference.seconds);
    if (!parser.has("out") && !outDir.empty()) std::filesystem::create_directories(outDir);
    writeImage(out, reference.image);
    std::printf("%s\n", out.c_str());
    return 0;
}

} // namespace vplgi
