// One field list per parameter struct (visitParams) feeds the CLI (--set key=value), scene files,
// the viewer UI and the configuration dump printed with every render and report.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace vplgi {

using Settings = std::vector<std::pair<std::string, std::string>>; // "key" -> "value", in order

class ParamVisitor {
public:
    virtual ~ParamVisitor() = default;
    virtual void field(const std::string& key, float& value, float min, float max, const char* doc) = 0;
    virtual void field(const std::string& key, int& value, int min, int max, const char* doc) = 0;
    virtual void field(const std::string& key, bool& value, const char* doc) = 0;
    virtual void field(const std::string& key, std::uint32_t& value, const char* doc) = 0;
    // A field with named values (an enum as an index into `names`). Visitors that do not care about
    // the names see an int field in [0, names.size() - 1].
    virtual void choice(const std::string& key, int& index, const std::vector<std::string>& names, const char* doc)
    {
        field(key, index, 0, static_cast<int>(names.size()) - 1, doc);
    }
    // The same kept as the chosen name, for lists not fixed at compile time (renderer.display: its
    // names include the technique's debug views). Forwards to the index form, so every visitor
    // handles it; `value` must be one of `names` (throws Error naming the key otherwise).
    virtual void choice(const std::string& key, std::string& value, const std::vector<std::string>& names,
                        const char* doc);
};

// Applies "key=value" settings to the fields it visits. Values out of range or unparsable throw
// Error naming the key. Call finish() after visiting everything: unknown keys throw there.
class ParamSetter final : public ParamVisitor {
public:
    explicit ParamSetter(Settings settings);
    void field(const std::string& key, float& value, float min, float max, const char* doc) override;
    void field(const std::string& key, int& value, int min, int max, const char* doc) override;
    void field(const std::string& key, bool& value, const char* doc) override;
    void field(const std::string& key, std::uint32_t& value, const char* doc) override;
    // Accepts a name of `names` (or its index).
    using ParamVisitor::choice;
    void choice(const std::string& key, int& index, const std::vector<std::string>& names, const char* doc) override;
    void finish() const;
    // Keys that matched a visited field (for callers that apply one setting list to several owners).
    const std::set<std::string>& usedKeys() const { return mUsed; }
    // Keys whose field got a different value (what a live change must apply or rebuild).
    const std::set<std::string>& changedKeys() const { return mChanged; }

private:
    const std::string* find(const std::string& key);
    Settings mSettings; // later entries win
    std::set<std::string> mUsed;
    std::set<std::string> mChanged;
    std::vector<std::string> mKnown;
};

// Collects "key = value  # doc [min, max]" lines (the effective configuration).
class ParamDumper final : public ParamVisitor {
public:
    void field(const std::string& key, float& value, float min, float max, const char* doc) override;
    void field(const std::string& key, int& value, int min, int max, const char* doc) override;
    void field(const std::string& key, bool& value, const char* doc) override;
    void field(const std::string& key, std::uint32_t& value, const char* doc) override;
    using ParamVisitor::choice;
    void choice(const std::string& key, int& index, const std::vector<std::string>& names, const char* doc) override;
    std::string text() const;                              // one line per field
    const std::map<std::string, std::string>& values() const { return mValues; }

private:
    std::vector<std::string> mLines;
    std::map<std::string, std::string> mValues;
};

// Splits "key=value"; throws Error for a missing '=' or empty key.
std::pair<std::string, std::string> parseSetting(const std::string& text);

} // namespace vplgi
