// What the subcommands share. The options: render, view, bench, compare and reference declare
// --scene, --camera, --set, --technique, --width/--height and --frames/--fps here, each with its own
// defaults (and, where the meaning differs, its own help). The session: load the scene description,
// resolve technique and parameters (scene-file settings, then --set on the command line; unknown keys
// are errors), pick the camera, then create the renderer once a GL context is current.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/util/params.h"
#include "core/scene/scene_loader.h"
#include "gl/api/shader_loader.h"
#include "gl/renderer.h"

namespace vplgi {

struct SessionOptions {
    std::string sceneSpec;
    std::string technique;  // empty: the scene file's, else "direct"
    std::string camera;     // empty: the scene's first camera
    Settings settings;      // --set, applied after the scene file's
    // When false, settings no field of this session knows are left for the caller to check (compare
    // applies one --set list to several techniques); see Session::usedKeys().
    bool rejectUnknownSettings = true;
    // When set, the session copies this scene instead of loading sceneSpec again (conform renders one
    // scene many times; sceneSpec still names it).
    std::shared_ptr<const SceneDescription> loaded;
};

class OptionParser;

// --scene S, --camera NAME and the repeatable --set KEY=VALUE (whose help says what the command's
// parameters are).
void addSceneOptions(OptionParser& parser, const std::string& setHelp);
// --technique T.
void addTechniqueOption(OptionParser& parser, const std::string& help, const std::string& defaultValue = "");
// --width W and --height H in pixels; `what` names the size ("image", "window").
void addSizeOptions(OptionParser& parser, const std::string& what, int width, int height);
// --frames N (the command says what its frames are) and --fps F (animation time is frame / fps).
void addAnimationOptions(OptionParser& parser, const std::string& framesHelp, int frames);

struct SceneOptions {
    std::string sceneSpec;
    std::string camera; // empty: the scene's first camera
    Settings settings;  // --set, in order
};
SceneOptions sceneOptions(const OptionParser& parser); // throws Error when --scene is missing

struct ImageSize {
    int width = 0;
    int height = 0;
};
ImageSize imageSize(const OptionParser& parser, int min, int max);

struct AnimationOptions {
    int frames = 1;
    float fps = 30.0f;
    float timeOf(int frame) const { return static_cast<float>(frame) / fps; }
};
AnimationOptions animationOptions(const OptionParser& parser, int maxFrames);

// What render and view take: --scene, --technique, --camera, --set.
void addSessionOptions(OptionParser& parser);
SessionOptions sessionOptions(const OptionParser& parser);

// The scene's camera called `name` (empty: the first); a scene without cameras gets the default one.
// Throws Error naming the cameras there are.
const Camera& resolveCamera(Scene& scene, const std::string& name);

// "name" or "name[key=value;key=value]" (compare's and conform's --techniques): the technique and
// the settings it gets after the command's --set ones. Throws Error on a malformed entry.
struct TechniqueEntry {
    std::string technique;
    Settings settings;
};
TechniqueEntry parseTechniqueEntry(const std::string& entry);

// A technique's radiance minus its direct light: the indirect part (compare's indirect, clamped and
// onebounce references, conform).
ImageRGBA32F indirectPart(const Renderer& renderer);

class Session;
// `settings` after {renderer.antialias = none}: what compare, bench and conform measure and show is
// never antialiased unless a --set asks for it.
Settings measuringSettings(const Settings& settings);
// Sessions of one scene with several techniques (compare, bench): each gets its settings list (after
// measuringSettings'); keys no session (and no field in `alsoKnown`) recognises are an error, checked
// before any GL work.
std::vector<std::unique_ptr<Session>> createSessions(const std::string& sceneSpec, const std::string& camera,
                                                     const std::vector<std::string>& techniques,
                                                     const std::vector<Settings>& settingsPerTechnique,
                                                     const std::set<std::string>& alsoKnown = {});

class Session {
public:
    explicit Session(const SessionOptions& options);  // CPU only: throws Error on any bad input
    // Needs a current GL context; `progress` gets the technique's long precomputations.
    void createRenderer(ProgressSink progress = terminalProgressBar());

    Scene& scene() { return mDescription.scene; }
    Camera& camera() { return mCamera; }
    Renderer& renderer() { return *mRenderer; }
    const std::string& techniqueName() const { return mTechniqueName; }
    const std::string& cameraName() const { return mCameraName; }
    // Applies every animation of the scene at `time`; returns true when a light moved.
    bool applyAnimations(float time);
    const std::set<std::string>& usedKeys() const { return mUsedKeys; }
    // "key = value  # doc" lines of every parameter in effect.
    std::string configuration();
    // Only the parameter lines of configuration(): every key with its value, range or choices and doc
    // (`vplgi render --list-params`).
    std::string parameterList();
    // The technique's own seed keys ("<group>.seed"; not the renderer's lights.seed, not
    // reference.seed): what `conform` and `compare --seeds` set to 1..N. Empty for a technique without
    // randomness of its own.
    std::vector<std::string> techniqueSeedKeys();

private:
    void visitAll(ParamVisitor& visitor);
    SceneDescription mDescription;
    std::set<std::string> mUsedKeys;
    std::string mTechniqueName;
    std::string mCameraName;
    Camera mCamera;
    RendererParams mParams;                // handed to the renderer in createRenderer(), then unused
    std::unique_ptr<Technique> mTechnique; // handed to the renderer in createRenderer()
    std::unique_ptr<gl::ShaderLoader> mShaders;
    std::unique_ptr<Renderer> mRenderer;
};

} // namespace vplgi
