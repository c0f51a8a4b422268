// What `render` and `view` share: load the scene description, resolve technique and parameters
// (scene-file settings, then --set on the command line; unknown keys are errors), pick the camera,
// then create the renderer once a GL context is current.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/params.h"
#include "core/scene_loader.h"
#include "gl/api/shader_loader.h"
#include "gl/renderer.h"

namespace vplgi {

struct SessionOptions {
    std::string sceneSpec;
    std::string technique;  // empty: the scene file's, else "direct"
    std::string camera;     // empty: the scene's first camera
    std::vector<std::pair<std::string, std::string>> settings; // --set, applied after the scene file's
    // When false, settings no field of this session knows are left for the caller to check (compare
    // applies one --set list to several techniques); see Session::usedKeys().
    bool rejectUnknownSettings = true;
};

class OptionParser;
// Declares --scene, --technique, --camera, --set on a subcommand's parser, and reads them back.
void addSessionOptions(OptionParser& parser);
SessionOptions sessionOptions(const OptionParser& parser);

class Session;
// Sessions of one scene with several techniques (compare, bench): each gets its settings list; keys
// no session (and no field in `alsoKnown`) recognises are an error, checked before any GL work.
std::vector<std::unique_ptr<Session>> createSessions(const std::string& sceneSpec, const std::string& camera,
                                                     const std::vector<std::string>& techniques,
                                                     const std::vector<Settings>& settingsPerTechnique,
                                                     const std::set<std::string>& alsoKnown = {});

class Session {
public:
    explicit Session(const SessionOptions& options);  // CPU only: throws Error on any bad input
    void createRenderer();                            // needs a current GL context

    Scene& scene() { return mDescription.scene; }
    Camera& camera() { return mCamera; }
    Renderer& renderer() { return *mRenderer; }
    const std::string& techniqueName() const { return mTechniqueName; }
    // Applies every animation of the scene at `time`; returns true when a light moved.
    bool applyAnimations(float time);
    const std::set<std::string>& usedKeys() const { return mUsedKeys; }
    // "key = value  # doc" lines of every parameter in effect.
    std::string configuration();

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
