// Technique "direct": no indirect light. The baseline every GI technique is compared with, and
// the check that the renderer's direct light matches the CPU (tests/image/test_direct_images.cpp).
#pragma once

#include "technique.h"

namespace vplgi {

class DirectTechnique final : public Technique {
public:
    std::string_view name() const override { return "direct"; }
    void setScene(const SceneContext&) override {}
    void update(const FrameContext&) override {}
    void render(const FrameContext&, const GBuffer&, const IndirectTarget&) override {}
    void visitParams(ParamVisitor&) override {}
};

} // namespace vplgi
