// One headless EGL context for the whole GL test binary, with KHR_debug errors turned into test
// failures (checkDebugMessages throws), and helpers for image tests.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/util/image_io.h"
#include "gl/api/objects.h"
#include "gl/api/shader_loader.h"
#include "core/util/params.h"
#include "gl/renderer.h"

namespace vplgi::test {

// Creates the context on first use; every GL test calls this first.
void ensureGLContext();
// The GPU-vs-CPU-twin checks were sized on llvmpipe, which computes in IEEE float with exact filter
// weights and attribute interpolation. A hardware GPU may filter with 8-bit fixed-point weights, snap
// vertices to an 8-bit sub-pixel grid, fuse multiply-adds and use approximate sqrt, exp, log and
// division, so those checks take `hardware` there: about 2.5x the error measured on an NVIDIA H200
// (driver 580.159; docs/conformance.md, "On a GPU"), each named at its check. A formula slip still
// shows up orders of magnitude above either bound.
bool onHardwareGPU();
template <class T>
T twinTolerance(T software, T hardware)
{
    return onHardwareGPU() ? hardware : software;
}
// The project's glsl/ directory.
const gl::ShaderLoader& shaders();
// The KHR_debug label of a GL object.
std::string objectLabel(GLenum identifier, GLuint id);
// Writes `image` under the test output directory (for failures) and returns the path.
std::string saveTestImage(const std::string& name, const ImageRGBA32F& image);
// A GL_R32F texture of width x height (`levels` mip levels) with `texels` (row-major, width * height)
// in level 0: the importance maps the sampler tests build.
gl::Texture uploadR32F(const std::string& label, const std::vector<float>& texels, int width, int height, int levels = 1);
// Runs the compute probe tests/gl/glsl/<file> (local size 64, SSBO 0 the `count` input cases,
// SSBO 1 resultsPerCase vec4 per case, uniform uCount) and returns the results: how the GL tests
// evaluate a shared header in GLSL next to its C++ build.
std::vector<glm::vec4> runComputeProbe(const std::string& name, const std::string& file, const void* cases,
                                       std::size_t caseBytes, int count, int resultsPerCase);
// A renderer of `scene` with technique `name`, the renderer's and the technique's fields set from
// `settings` (key -> value, as --set); throws Error on an unknown key.
std::unique_ptr<Renderer> makeTechniqueRenderer(const Scene& scene, const std::string& name,
                                                const Settings& settings);
// Renders one frame and returns the radiance minus the direct light: the technique's indirect
// light (rows top to bottom).
ImageRGBA32F renderIndirect(Renderer& renderer, const Camera& camera, int width, int height);

} // namespace vplgi::test
