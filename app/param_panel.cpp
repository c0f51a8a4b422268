#include "param_panel.h"

#include <imgui.h>

#include <cstdio>
#include <sstream>

namespace vplgi {

namespace {

// "[m]" in a doc string is the field's unit (STYLE.md: every field's comment has its units); shown
// after the value. Brackets holding digits are ranges, not units.
std::string unitOf(const char* doc)
{
    const std::string text = doc ? doc : "";
    const std::size_t open = text.rfind('[');
    const std::size_t close = text.rfind(']');
    if (open == std::string::npos || close == std::string::npos || close < open + 2) return "";
    const std::string unit = text.substr(open + 1, close - open - 1);
    if (unit.find_first_of("0123456789,") != std::string::npos) return "";
    std::string escaped; // it goes into a printf format
    for (char c : unit)
        escaped += c == '%' ? std::string("%%") : std::string(1, c);
    return escaped;
}

std::string label(const std::string& key)
{
    const std::size_t dot = key.find('.');
    return (dot == std::string::npos ? key : key.substr(dot + 1)) + "##" + key;
}

template <typename T> std::string text(T value)
{
    std::ostringstream s;
    s.precision(9); // round-trips a float through ParamSetter's strtod
    s << value;
    return s.str();
}

} // namespace

void ParamPanel::begin()
{
    mKeys.clear();
    mGroup.clear();
    mGroupOpen = false;
}

void ParamPanel::end()
{
    mGroup.clear();
}

bool ParamPanel::openGroup(const std::string& key)
{
    mKeys.push_back(key);
    const std::string group = key.substr(0, key.find('.'));
    if (group != mGroup) {
        mGroup = group;
        mGroupOpen = ImGui::CollapsingHeader(group.c_str(), ImGuiTreeNodeFlags_DefaultOpen);
    }
    return mGroupOpen;
}

void ParamPanel::tooltip(const std::string& key, const char* doc, const std::string& range)
{
    if (!ImGui::IsItemHovered()) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
    ImGui::TextUnformatted(key.c_str());
    ImGui::TextUnformatted(doc ? doc : "");
    if (!range.empty()) ImGui::TextDisabled("%s", range.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

void ParamPanel::edit(const std::string& key, const std::string& value)
{
    mEdits.emplace_back(key, value);
}

Settings ParamPanel::takeEdits()
{
    Settings edits;
    edits.swap(mEdits);
    return edits;
}

void ParamPanel::field(const std::string& key, float& value, float min, float max, const char* doc)
{
    if (!openGroup(key)) return;
    const std::string format = "%.4g " + unitOf(doc);
    // Ranges spanning decades (exposure [0, 1e6]) get a logarithmic slider; ctrl+click types a value.
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_NoRoundToFormat;
    if (max - min > 1000.0f) flags |= ImGuiSliderFlags_Logarithmic;
    float shown = value;
    if (ImGui::SliderFloat(label(key).c_str(), &shown, min, max, format.c_str(), flags) && shown != value)
        edit(key, text(shown)); // floats are cheap to change: applied while dragging
    tooltip(key, doc, "[" + text(min) + ", " + text(max) + "]");
}

void ParamPanel::field(const std::string& key, int& value, int min, int max, const char* doc)
{
    if (!openGroup(key)) return;
    const std::string format = "%d " + unitOf(doc);
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
    if (static_cast<double>(max) - min > 256.0) flags |= ImGuiSliderFlags_Logarithmic;
    auto dragging = mDragging.find(key);
    int shown = dragging != mDragging.end() ? static_cast<int>(dragging->second) : value;
    if (ImGui::SliderInt(label(key).c_str(), &shown, min, max, format.c_str(), flags)) mDragging[key] = shown;
    if (ImGui::IsItemDeactivated()) {
        if (shown != value) edit(key, text(shown));
        mDragging.erase(key);
    }
    tooltip(key, doc, "[" + text(min) + ", " + text(max) + "]");
}

void ParamPanel::field(const std::string& key, bool& value, const char* doc)
{
    if (!openGroup(key)) return;
    bool shown = value;
    if (ImGui::Checkbox(label(key).c_str(), &shown)) edit(key, shown ? "true" : "false");
    tooltip(key, doc, "");
}

void ParamPanel::field(const std::string& key, std::uint32_t& value, const char* doc)
{
    if (!openGroup(key)) return;
    std::uint32_t shown = value;
    const std::uint32_t step = 1;
    if (ImGui::InputScalar(label(key).c_str(), ImGuiDataType_U32, &shown, &step, nullptr, "%u") && shown != value)
        edit(key, text(shown));
    tooltip(key, doc, "[0, 4294967295]");
}

void ParamPanel::choice(const std::string& key, int& index, const std::vector<std::string>& names, const char* doc)
{
    if (!openGroup(key)) return;
    const char* current = index >= 0 && index < static_cast<int>(names.size()) ? names[index].c_str() : "?";
    if (ImGui::BeginCombo(label(key).c_str(), current)) {
        for (std::size_t i = 0; i < names.size(); ++i) {
            const bool selected = static_cast<int>(i) == index;
            if (ImGui::Selectable(names[i].c_str(), selected) && !selected) edit(key, names[i]);
            if (selected) ImGui::SetItemDefaultFocus();
        }
        ImGui::EndCombo();
    }
    std::string options;
    for (const std::string& n : names)
        options += (options.empty() ? "" : " | ") + n;
    tooltip(key, doc, options);
}

} // namespace vplgi
