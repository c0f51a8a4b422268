#include "session.h"

#include <sstream>

#include "core/scene/builtin_scenes.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "cli.h"

namespace vplgi {

void addSceneOptions(OptionParser& parser, const std::string& setHelp)
{
    std::string names;
    for (const std::string& name : builtinSceneNames()) names += (names.empty() ? "" : ", ") + name;
    parser.value("scene", "S", "built-in scene (" + names + "), scene file (.json) or .gltf/.glb");
    parser.value("camera", "NAME", "camera name (default: the scene's first camera)");
    parser.value("set", "KEY=VALUE", setHelp, "", true);
}

void addTechniqueOption(OptionParser& parser, const std::string& help, const std::string& defaultValue)
{
    parser.value("technique", "T", help, defaultValue);
}

void addSizeOptions(OptionParser& parser, const std::string& what, int width, int height)
{
    parser.value("width", "W", what + " width in pixels", std::to_string(width));
    parser.value("height", "H", what + " height in pixels", std::to_string(height));
}

void addAnimationOptions(OptionParser& parser, const std::string& framesHelp, int frames)
{
    parser.value("frames", "N", framesHelp, std::to_string(frames));
    parser.value("fps", "F", "animation frames per second (animations advance 1/fps per frame)", "30");
}

SceneOptions sceneOptions(const OptionParser& parser)
{
    require(parser.has("scene"), "--scene is required (e.g. --scene cornell)");
    SceneOptions options;
    options.sceneSpec = parser.get("scene");
    options.camera = parser.get("camera");
    for (const std::string& s : parser.getAll("set")) options.settings.push_back(parseSetting(s));
    return options;
}

ImageSize imageSize(const OptionParser& parser, int min, int max)
{
    return {parser.getInt("width", min, max), parser.getInt("height", min, max)};
}

AnimationOptions animationOptions(const OptionParser& parser, int maxFrames)
{
    return {parser.getInt("frames", 1, maxFrames), parser.getFloat("fps", 0.001f, 10000.0f)};
}

void addSessionOptions(OptionParser& parser)
{
    addSceneOptions(parser, "set a parameter, e.g. renderer.exposure=2");
    addTechniqueOption(parser, "GI technique (default: the scene file's, else direct)");
}

SessionOptions sessionOptions(const OptionParser& parser)
{
    SceneOptions scene = sceneOptions(parser);
    SessionOptions options;
    options.sceneSpec = scene.sceneSpec;
    options.technique = parser.get("technique");
    options.camera = scene.camera;
    options.settings = scene.settings;
    return options;
}

const Camera& resolveCamera(Scene& scene, const std::string& name)
{
    if (scene.cameras.empty()) scene.cameras.push_back(makeDefaultCamera(scene.worldBounds()));
    const std::string wanted = name.empty() ? scene.cameras.front().name : name;
    const Camera* camera = scene.findCamera(wanted);
    if (!camera) {
        std::string known;
        for (const Camera& c : scene.cameras) known += (known.empty() ? "" : ", ") + c.name;
        throw Error("scene " + scene.name + " has no camera \"" + wanted + "\" (cameras: " + known + ")");
    }
    return *camera;
}

Session::Session(const SessionOptions& options)
    : mDescription(options.loaded ? *options.loaded : loadSceneSpec(options.sceneSpec))
{
    mTechniqueName = !options.technique.empty() ? options.technique
                     : !mDescription.technique.empty() ? mDescription.technique
                                                       : "direct";
    mTechnique = createTechnique(mTechniqueName);

    Settings settings = mDescription.settings;
    settings.insert(settings.end(), options.settings.begin(), options.settings.end());
    ParamSetter setter(settings);
    visitAll(setter);
    if (options.rejectUnknownSettings) setter.finish();
    mUsedKeys = setter.usedKeys();

    mCamera = resolveCamera(mDescription.scene, options.camera);
    mCameraName = mCamera.name;
}

void Session::visitAll(ParamVisitor& visitor)
{
    // Before createRenderer() the fields live here; afterwards only in the renderer (one live set).
    if (mRenderer) {
        mRenderer->visitParams(visitor);
        return;
    }
    mParams.visitParams(visitor, displayViewNames(mTechnique ? mTechnique->debugViews() : std::vector<DebugView>{}));
    if (mTechnique) mTechnique->visitParams(visitor);
}

void Session::createRenderer(ProgressSink progress)
{
    mShaders = std::make_unique<gl::ShaderLoader>();
    mRenderer = std::make_unique<Renderer>(*mShaders, mDescription.scene, mParams, std::move(mTechnique),
                                           std::move(progress));
}

bool Session::applyAnimations(float time)
{
    bool lightMoved = false;
    for (const Animation& animation : mDescription.scene.animations) {
        applyAnimation(mDescription.scene, animation, time);
        if (animation.targetKind == Animation::Target::Light) lightMoved = true;
        else if (animation.targetName == mCameraName) mCamera = *mDescription.scene.findCamera(mCameraName);
    }
    if (lightMoved && mRenderer) mRenderer->markLightsChanged();
    return lightMoved;
}

std::string Session::configuration()
{
    ParamDumper dumper;
    visitAll(dumper);
    return "scene = " + mDescription.scene.source + "\ntechnique = " + mTechniqueName + "\ncamera = " + mCameraName +
           "\n" + dumper.text();
}

std::vector<std::string> Session::techniqueSeedKeys()
{
    std::vector<std::string> keys;
    std::stringstream lines(parameterList());
    for (std::string line; std::getline(lines, line);) {
        const std::string key = line.substr(0, line.find(' '));
        const std::size_t dot = key.rfind('.');
        if (dot == std::string::npos || key.substr(dot + 1) != "seed") continue;
        if (key == "lights.seed" || key.rfind("reference.", 0) == 0) continue;
        keys.push_back(key);
    }
    return keys;
}

std::string Session::parameterList()
{
    ParamDumper dumper;
    visitAll(dumper);
    return dumper.text();
}

Settings measuringSettings(const Settings& settings)
{
    Settings out = {{"renderer.antialias", "none"}};
    out.insert(out.end(), settings.begin(), settings.end());
    return out;
}

std::vector<std::unique_ptr<Session>> createSessions(const std::string& sceneSpec, const std::string& camera,
                                                     const std::vector<std::string>& techniques,
                                                     const std::vector<Settings>& settingsPerTechnique,
                                                     const std::set<std::string>& alsoKnown)
{
    std::vector<std::unique_ptr<Session>> sessions;
    std::set<std::string> used = alsoKnown;
    for (std::size_t i = 0; i < techniques.size(); ++i) {
        SessionOptions options;
        options.sceneSpec = sceneSpec;
        options.technique = techniques[i];
        options.camera = camera;
        options.settings = measuringSettings(settingsPerTechnique[i]);
        options.rejectUnknownSettings = false;
        sessions.push_back(std::make_unique<Session>(options));
        used.insert(sessions.back()->usedKeys().begin(), sessions.back()->usedKeys().end());
    }
    for (const Settings& settings : settingsPerTechnique)
        for (const auto& setting : settings)
            require(used.count(setting.first) > 0, "unknown parameter \"" + setting.first + "\"");
    return sessions;
}

ImageRGBA32F indirectPart(const Renderer& renderer)
{
    ImageRGBA32F total = renderer.readRadiance();
    const ImageRGBA32F direct = renderer.readDirect();
    for (std::size_t i = 0; i < total.pixels.size(); ++i)
        if (i % 4 != 3) total.pixels[i] -= direct.pixels[i];
    return total;
}

TechniqueEntry parseTechniqueEntry(const std::string& entry)
{
    TechniqueEntry result;
    const std::size_t open = entry.find('[');
    if (open == std::string::npos) {
        result.technique = entry;
        return result;
    }
    require(entry.back() == ']' && open > 0,
            "--techniques: \"" + entry + "\" must be name or name[key=value;key=value]");
    result.technique = entry.substr(0, open);
    std::stringstream list(entry.substr(open + 1, entry.size() - open - 2));
    for (std::string item; std::getline(list, item, ';');)
        if (!item.empty()) result.settings.push_back(parseSetting(item));
    return result;
}

} // namespace vplgi
