// Debug views: textures the display can show instead of the final image (issue 8 part 10).
// Techniques list theirs in Technique::debugViews() (gl/techniques/technique.h), the renderer adds
// its own (the shadow maps); renderer.display picks one by name.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "api/objects.h"
#include "glsl/shared/bindings.h"

namespace vplgi {

// A texture a technique (or the renderer) can show instead of the final image: `--set
// renderer.display=<name>` (the CLI, a scene file, the viewer) picks it by name, and the tone-map
// pass draws it scaled to the output size (nearest texel; layer `layer` + renderer.displayLayer, or
// all `layerCount` layers tiled row by row from the top left when renderer.displayLayer is -1).
// How a view turns into display values is its `kind` (glsl/shared/bindings.h kDebugView*):
//   kDebugViewColor   rgb HDR colour, tone mapped with renderer.exposure like the final image
//   kDebugViewScalar  r mapped linearly from [range.x, range.y] to black..white (depth, distance)
//   kDebugViewNormal  xyz as xyz * 0.5 + 0.5
//   kDebugViewCount   r >= 0 as log2(1 + r) / log2(1 + range.y) (counts span decades)
// Any float or normalised format of any texture target is fine (2D, 2D array, cube map, cube-map
// array: the pass reads it through a 2D-array texture view, so a cube-map array's layer is
// cube * 6 + face); integer formats are not (they need another sampler type). debugViews() is
// called every displayed frame, so a view may follow the technique's own parameters (e.g. the
// atlas tile of the VPL that a `smcir.debugVpl` names, as `layer` and `rect`).
//
// Example, in a technique with an RSM and a shadow atlas:
//   std::vector<DebugView> debugViews() const override {
//       return {{"smcir.atlas", "shadow-atlas depth, one layer", &mAtlas.texture(), shared::kDebugViewScalar},
//               {"vsgl.flux", "RSM flux of light 0", rsmFluxOrNull(), shared::kDebugViewColor}};
//   }
struct DebugView {
    std::string name;                     // "<technique>.<what>", e.g. "smcir.atlas"; unique, stable
    std::string description;              // one line, for listings and the viewer
    const gl::Texture* texture = nullptr; // null (or not yet created): shows black
    int kind = 0;                         // shared::kDebugView*
    glm::vec2 range{0.0f, 1.0f};          // scalar: the values shown as black and white; count: y = the maximum
    int level = 0;                        // mip level
    int layer = 0;                        // first layer shown (array and cube textures)
    int layerCount = 1;                   // layers that renderer.displayLayer = -1 tiles; 0: up to the last
    glm::ivec4 rect{0};                   // x, y, width, height in texels of `level`; zero width: the whole level
};

} // namespace vplgi
