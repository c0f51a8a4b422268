// The per-frame uniform block (glsl/shared/bindings.h).
#include "../shared/bindings.h"

layout(std140, binding = kBindingFrame) uniform FrameBlock {
    FrameUniforms frame;
};
