#include "technique.h"

#include "core/error.h"
#include "direct_technique.h"

namespace vplgi {

std::vector<std::string> techniqueNames()
{
    return {"direct"};
}

std::unique_ptr<Technique> createTechnique(std::string_view name)
{
    if (name == "direct") return std::make_unique<DirectTechnique>();
    std::string known;
    for (const std::string& n : techniqueNames()) known += (known.empty() ? "" : ", ") + n;
    throw Error("unknown technique \"" + std::string(name) + "\" (known: " + known + ")");
}

} // namespace vplgi
