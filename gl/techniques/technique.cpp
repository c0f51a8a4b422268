#include "technique.h"

#include "core/util/error.h"
#include "direct_technique.h"
#include "lightskin_technique.h"
#include "smcir_rt_technique.h"
#include "vpl_technique.h"
#include "vsgl_technique.h"

namespace vplgi {

std::vector<std::string> techniqueNames()
{
    return {"direct", "ir", "lightskin", "lightskin-full", "mir", "smcir", "smcir-rt", "tcas", "vpl-brsm", "vsgl"};
}

std::unique_ptr<Technique> createTechnique(std::string_view name)
{
    if (name == "direct") return std::make_unique<DirectTechnique>();
    if (name == "ir") return std::make_unique<VPLTechnique>(VPLTechnique::Source::IR);
    if (name == "mir") return std::make_unique<VPLTechnique>(VPLTechnique::Source::MIR);
    if (name == "lightskin") return std::make_unique<LightSkinTechnique>(false);
    if (name == "lightskin-full") return std::make_unique<LightSkinTechnique>(true);
    if (name == "smcir") return std::make_unique<VPLTechnique>(VPLTechnique::Source::SMCIR);
    if (name == "smcir-rt") return std::make_unique<SMCIRRayTracedTechnique>();
    if (name == "vsgl") return std::make_unique<VSGLTechnique>(VSGLParams::VSGL);
    if (name == "vpl-brsm") return std::make_unique<VSGLTechnique>(VSGLParams::VPLBRSM);
    if (name == "tcas") return std::make_unique<VSGLTechnique>(VSGLParams::TCAS);
    std::string known;
    for (const std::string& n : techniqueNames()) known += (known.empty() ? "" : ", ") + n;
    throw Error("unknown technique \"" + std::string(name) + "\" (known: " + known + ")");
}

} // namespace vplgi
