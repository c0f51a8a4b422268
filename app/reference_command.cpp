// `vplgi reference`: the Embree path tracer (core/path_tracer.h) from the command line.
#include <cstdio>
#include <filesystem>

#include "cli.h"
#include "commands.h"
#include "core/error.h"
#include "core/params.h"
#include "core/scene_loader.h"
#include "reference.h"

namespace vplgi {

int runReference(const std::vector<std::string>& args)
{
    OptionParser parser("vplgi reference",
                        "Path-traces a ground-truth image (Embree, multi-threaded, deterministic for a seed and\n"
                        "any thread count) and writes linear radiance to an EXR. Modes (SMCIR Fig. 8): full,\n"
                        "direct, indirect (at least one bounce after the primary hit: what VPL methods estimate),\n"
                        "clamped (indirect with the geometry term leaving the primary hit clamped).");
    parser.value("scene", "S", "built-in scene, scene file (.json) or .gltf/.glb");
    parser.value("camera", "NAME", "camera name (default: the scene's first camera)");
    parser.value("mode", "M", "full, direct, indirect, clamped or onebounce", "full");
    parser.value("spp", "N", "samples per pixel", "64");
    parser.value("width", "W", "image width", "640");
    parser.value("height", "H", "image height", "360");
    parser.value("time-budget", "S", "stop after the pass that crosses S seconds (0 = none)", "0");
    parser.value("out", "FILE", "output .exr (linear radiance)", "out/reference.exr");
    parser.value("cache", "DIR", "reference cache directory ($VPLGI_CACHE_DIR or out/reference-cache)");
    parser.flag("no-cache", "neither read nor write the cache");
    parser.value("set", "KEY=VALUE", "set a reference.* parameter (e.g. reference.maxDepth=3)", "", true);
    if (!parser.parse(args)) return 0;

    require(parser.has("scene"), "--scene is required (e.g. --scene cornell)");
    const int width = parser.getInt("width", 1, 16384);
    const int height = parser.getInt("height", 1, 16384);
    const std::string out = parser.get("out");
    require(isFloatImagePath(out), out + ": the reference is linear radiance: write an .exr");
    std::filesystem::path outDir = std::filesystem::path(out).parent_path();
    if (parser.has("out") && !outDir.empty())
        require(std::filesystem::is_directory(outDir), out + ": directory " + outDir.string() + " does not exist");

    PathTracerParams params;
    params.mode = parseReferenceMode(parser.get("mode"));
    params.spp = parser.getInt("spp", 1, 1 << 24);
    params.timeBudgetSeconds = parser.getFloat("time-budget", 0.0f, 1e7f);
    Settings settings;
    for (const std::string& s : parser.getAll("set")) settings.push_back(parseSetting(s));
    ParamSetter setter(settings);
    params.visitParams(setter);
    setter.finish();

    SceneDescription description = loadSceneSpec(parser.get("scene"));
    Scene& scene = description.scene;
    if (scene.cameras.empty()) scene.cameras.push_back(makeDefaultCamera(scene.worldBounds()));
    const std::string cameraName = parser.has("camera") ? parser.get("camera") : scene.cameras.front().name;
    const Camera* camera = scene.findCamera(cameraName);
    require(camera != nullptr, "scene " + scene.name + " has no camera \"" + cameraName + "\"");

    ParamDumper dumper;
    params.visitParams(dumper);
    std::printf("scene = %s\ncamera = %s\n%s", scene.source.c_str(), cameraName.c_str(), dumper.text().c_str());
    RayScene rays(scene);
    ReferenceRequest request{scene, rays, *camera, width, height, params,
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
