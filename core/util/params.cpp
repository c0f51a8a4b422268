#include "core/util/params.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "core/util/error.h"

namespace vplgi {

std::pair<std::string, std::string> parseSetting(const std::string& text)
{
    std::size_t eq = text.find('=');
    require(eq != std::string::npos && eq > 0, "--set \"" + text + "\": expected key=value");
    return {text.substr(0, eq), text.substr(eq + 1)};
}

void ParamVisitor::choice(const std::string& key, std::string& value, const std::vector<std::string>& names,
                          const char* doc)
{
    const auto found = std::find(names.begin(), names.end(), value);
    require(found != names.end(), "parameter " + key + ": \"" + value + "\" is not one of its names");
    int index = static_cast<int>(found - names.begin());
    choice(key, index, names, doc);
    value = names[static_cast<std::size_t>(index)];
}

ParamSetter::ParamSetter(Settings settings)
    : mSettings(std::move(settings))
{
}

const std::string* ParamSetter::find(const std::string& key)
{
    mKnown.push_back(key);
    const std::string* found = nullptr;
    for (const auto& [k, v] : mSettings)
        if (k == key) found = &v;
    if (found) mUsed.insert(key);
    return found;
}

namespace {

double parseNumber(const std::string& key, const std::string& text)
{
    errno = 0;
    char* end = nullptr;
    double value = std::strtod(text.c_str(), &end);
    require(!text.empty() && end == text.c_str() + text.size() && errno == 0 && std::isfinite(value),
            "parameter " + key + ": \"" + text + "\" is not a number");
    return value;
}

template <typename T>
std::string rangeText(T min, T max)
{
    std::ostringstream s;
    s << "[" << min << ", " << max << "]";
    return s.str();
}

} // namespace

void ParamSetter::field(const std::string& key, float& value, float min, float max, const char*)
{
    if (const std::string* text = find(key)) {
        double v = parseNumber(key, *text);
        require(v >= min && v <= max, "parameter " + key + " = " + *text + " is outside " + rangeText(min, max));
        if (value != static_cast<float>(v)) mChanged.insert(key);
        value = static_cast<float>(v);
    }
}

void ParamSetter::field(const std::string& key, int& value, int min, int max, const char*)
{
    if (const std::string* text = find(key)) {
        double v = parseNumber(key, *text);
        require(v == std::floor(v), "parameter " + key + ": \"" + *text + "\" is not an integer");
        require(v >= min && v <= max, "parameter " + key + " = " + *text + " is outside " + rangeText(min, max));
        if (value != static_cast<int>(v)) mChanged.insert(key);
        value = static_cast<int>(v);
    }
}

void ParamSetter::field(const std::string& key, bool& value, const char*)
{
    if (const std::string* text = find(key)) {
        const bool before = value;
        if (*text == "1" || *text == "true" || *text == "on") value = true;
        else if (*text == "0" || *text == "false" || *text == "off") value = false;
        else throw Error("parameter " + key + ": \"" + *text + "\" is not a boolean (true/false)");
        if (value != before) mChanged.insert(key);
    }
}

void ParamSetter::field(const std::string& key, std::uint32_t& value, const char*)
{
    if (const std::string* text = find(key)) {
        double v = parseNumber(key, *text);
        require(v == std::floor(v) && v >= 0.0 && v <= 4294967295.0,
                "parameter " + key + ": \"" + *text + "\" is not an unsigned 32-bit integer");
        if (value != static_cast<std::uint32_t>(v)) mChanged.insert(key);
        value = static_cast<std::uint32_t>(v);
    }
}

void ParamSetter::choice(const std::string& key, int& index, const std::vector<std::string>& names, const char*)
{
    if (const std::string* text = find(key)) {
        std::string known;
        for (std::size_t i = 0; i < names.size(); ++i) {
            if (*text == names[i] || *text == std::to_string(i)) {
                if (index != static_cast<int>(i)) mChanged.insert(key);
                index = static_cast<int>(i);
                return;
            }
            known += (known.empty() ? "" : ", ") + names[i];
        }
        throw Error("parameter " + key + ": \"" + *text + "\" is not one of " + known);
    }
}

namespace {

// Levenshtein distance (insertions, deletions, substitutions), for "did you mean".
std::size_t editDistance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

} // namespace

void ParamSetter::finish() const
{
    for (const auto& setting : mSettings) {
        if (mUsed.count(setting.first)) continue;
        // The closest known key when it is a likely typo (at most a third of the key's letters off);
        // else the keys with the same prefix ("vsgl."), else every key.
        const std::string& key = setting.first;
        std::string closest;
        std::size_t best = key.size() / 3 + 1;
        for (const std::string& k : mKnown)
            if (const std::size_t d = editDistance(key, k); d < best) {
                best = d;
                closest = k;
            }
        if (!closest.empty()) throw Error("unknown parameter \"" + key + "\" (did you mean \"" + closest + "\"?)");
        const std::string prefix = key.substr(0, key.find('.') + 1);
        std::string known, sameGroup;
        for (const std::string& k : mKnown) {
            known += (known.empty() ? "" : ", ") + k;
            if (key.find('.') != std::string::npos && k.rfind(prefix, 0) == 0)
                sameGroup += (sameGroup.empty() ? "" : ", ") + k;
        }
        throw Error("unknown parameter \"" + key + "\" (known: " + (sameGroup.empty() ? known : sameGroup) + ")");
    }
}

namespace {

template <typename T>
std::string valueText(T value)
{
    std::ostringstream s;
    s << value;
    return s.str();
}

} // namespace

void ParamDumper::field(const std::string& key, float& value, float min, float max, const char* doc)
{
    mValues[key] = valueText(value);
    mLines.push_back(key + " = " + mValues[key] + "  # " + doc + " " + rangeText(min, max));
}

void ParamDumper::field(const std::string& key, int& value, int min, int max, const char* doc)
{
    mValues[key] = valueText(value);
    mLines.push_back(key + " = " + mValues[key] + "  # " + doc + " " + rangeText(min, max));
}

void ParamDumper::field(const std::string& key, bool& value, const char* doc)
{
    mValues[key] = value ? "true" : "false";
    mLines.push_back(key + " = " + mValues[key] + "  # " + doc);
}

void ParamDumper::field(const std::string& key, std::uint32_t& value, const char* doc)
{
    mValues[key] = valueText(value);
    mLines.push_back(key + " = " + mValues[key] + "  # " + doc);
}

void ParamDumper::choice(const std::string& key, int& index, const std::vector<std::string>& names, const char* doc)
{
    mValues[key] = index >= 0 && index < static_cast<int>(names.size()) ? names[static_cast<std::size_t>(index)]
                                                                         : valueText(index);
    std::string options;
    for (const std::string& n : names) options += (options.empty() ? "" : "|") + n;
    mLines.push_back(key + " = " + mValues[key] + "  # " + doc + " (" + options + ")");
}

std::string ParamDumper::text() const
{
    std::string out;
    for (const std::string& line : mLines) out += line + "\n";
    return out;
}

} // namespace vplgi
