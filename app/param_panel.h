// The viewer's parameter panel: a ParamVisitor that draws one Dear ImGui widget per field of the one
// field list (Renderer::visitParams: renderer, passes, technique), so the panel has no list of its
// own and a new technique's parameters appear without viewer code. Widgets never write the live
// fields: an edit becomes a "key=value" setting that the caller applies through
// Renderer::applySettings, the same path as --set, scene files and the viewer's --script, so
// structural changes rebuild what they must (Technique::applyParamChanges).
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/util/params.h"

namespace vplgi {

class ParamPanel final : public ParamVisitor {
public:
    // Call once per ImGui frame before visiting; fields are grouped under collapsing headers by
    // their key's prefix ("renderer", "shadow", "smcir", ...).
    void begin();
    void end();

    void field(const std::string& key, float& value, float min, float max, const char* doc) override;
    void field(const std::string& key, int& value, int min, int max, const char* doc) override;
    void field(const std::string& key, bool& value, const char* doc) override;
    void field(const std::string& key, std::uint32_t& value, const char* doc) override;
    using ParamVisitor::choice;
    void choice(const std::string& key, int& index, const std::vector<std::string>& names, const char* doc) override;

    // Edits of this frame, in order, as --set would write them; the caller applies and clears them.
    Settings takeEdits();
    // Every key the panel generated a widget for in the last frame (whether or not its header was open).
    const std::vector<std::string>& keys() const { return mKeys; }

private:
    bool openGroup(const std::string& key); // opens the key's header on a new prefix; false when collapsed
    void tooltip(const std::string& key, const char* doc, const std::string& range);
    void edit(const std::string& key, const std::string& value);

    std::vector<std::string> mKeys;
    std::string mGroup; // prefix of the header being drawn
    bool mGroupOpen = false;
    Settings mEdits;
    // Integer fields are applied when the slider is released (a structural one such as rsm.size
    // would otherwise rebuild at every step of a drag); their value while dragging lives here.
    std::map<std::string, double> mDragging;
};

} // namespace vplgi
