#include "cli.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/util/error.h"

namespace vplgi {

OptionParser::OptionParser(std::string command, std::string summary)
    : mCommand(std::move(command)), mSummary(std::move(summary))
{
    flag("help", "show this help and exit");
}

void OptionParser::value(const std::string& name, const std::string& metavar, const std::string& help,
                         const std::string& defaultValue, bool repeatable)
{
    mOptions.push_back({name, metavar, help, defaultValue, true, repeatable});
}

void OptionParser::flag(const std::string& name, const std::string& help)
{
    mOptions.push_back({name, "", help, "", false, false});
}

const OptionParser::Option* OptionParser::find(const std::string& name) const
{
    for (const Option& o : mOptions)
        if (o.name == name) return &o;
    return nullptr;
}

bool OptionParser::parse(const std::vector<std::string>& args)
{
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        require(arg.rfind("--", 0) == 0 && arg.size() > 2,
                "unexpected argument \"" + arg + "\" for '" + mCommand + "' (see " + mCommand + " --help)");
        std::string name = arg.substr(2), inlineValue;
        bool hasInline = false;
        if (std::size_t eq = name.find('='); eq != std::string::npos) {
            inlineValue = name.substr(eq + 1);
            name = name.substr(0, eq);
            hasInline = true;
        }
        const Option* option = find(name);
        require(option != nullptr, "unknown option --" + name + " for '" + mCommand + "' (see " + mCommand + " --help)");
        if (name == "help") {
            std::fputs(help().c_str(), stdout);
            return false;
        }
        if (!option->takesValue) {
            require(!hasInline, "option --" + name + " takes no value");
            mValues[name].push_back("1");
            continue;
        }
        std::string value;
        if (hasInline) {
            value = inlineValue;
        } else {
            require(i + 1 < args.size(), "option --" + name + " needs a value (" + option->metavar + ")");
            value = args[++i];
        }
        require(option->repeatable || mValues[name].empty(), "option --" + name + " given twice");
        mValues[name].push_back(value);
    }
    return true;
}

bool OptionParser::has(const std::string& name) const
{
    auto it = mValues.find(name);
    return it != mValues.end() && !it->second.empty();
}

std::string OptionParser::get(const std::string& name) const
{
    if (has(name)) return mValues.at(name).back();
    const Option* option = find(name);
    return option ? option->defaultValue : "";
}

std::vector<std::string> OptionParser::getAll(const std::string& name) const
{
    return has(name) ? mValues.at(name) : std::vector<std::string>{};
}

int OptionParser::getInt(const std::string& name, int min, int max) const
{
    std::string text = get(name);
    errno = 0;
    char* end = nullptr;
    long value = std::strtol(text.c_str(), &end, 10);
    require(!text.empty() && end == text.c_str() + text.size() && errno == 0,
            "--" + name + " \"" + text + "\" is not an integer");
    require(value >= min && value <= max,
            "--" + name + " " + text + " is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    return static_cast<int>(value);
}

float OptionParser::getFloat(const std::string& name, float min, float max) const
{
    std::string text = get(name);
    errno = 0;
    char* end = nullptr;
    double value = std::strtod(text.c_str(), &end);
    require(!text.empty() && end == text.c_str() + text.size() && errno == 0 && std::isfinite(value),
            "--" + name + " \"" + text + "\" is not a number");
    require(value >= min && value <= max, "--" + name + " " + text + " is outside [" + std::to_string(min) + ", " +
                                              std::to_string(max) + "]");
    return static_cast<float>(value);
}

std::string OptionParser::help() const
{
    std::string out = "usage: " + mCommand + " [options]\n\n" + mSummary + "\n\noptions:\n";
    for (const Option& o : mOptions) {
        std::string left = "  --" + o.name + (o.takesValue ? " " + o.metavar : "");
        if (left.size() < 28) left.resize(28, ' ');
        else left += "  ";
        out += left + o.help;
        if (!o.defaultValue.empty()) out += " (default: " + o.defaultValue + ")";
        if (o.repeatable) out += " (repeatable)";
        out += "\n";
    }
    return out;
}

} // namespace vplgi
