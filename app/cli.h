// Command-line parsing for the vplgi subcommands: every option is declared once with its help
// text; unknown options and bad values throw Error with one line naming the problem.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vplgi {

class OptionParser {
public:
    OptionParser(std::string command, std::string summary);
    // Declares an option taking a value (`--name VALUE`); repeatable ones collect every value.
    void value(const std::string& name, const std::string& metavar, const std::string& help,
               const std::string& defaultValue = "", bool repeatable = false);
    void flag(const std::string& name, const std::string& help);
    // Parses args (without the subcommand). Returns false when --help was given (help printed).
    bool parse(const std::vector<std::string>& args);

    bool has(const std::string& name) const;
    std::string get(const std::string& name) const;
    std::vector<std::string> getAll(const std::string& name) const;
    int getInt(const std::string& name, int min, int max) const;
    float getFloat(const std::string& name, float min, float max) const;
    std::string help() const;

private:
    struct Option {
        std::string name, metavar, help, defaultValue;
        bool takesValue = true;
        bool repeatable = false;
    };
    const Option* find(const std::string& name) const;
    std::string mCommand, mSummary;
    std::vector<Option> mOptions;
    std::map<std::string, std::vector<std::string>> mValues;
};

} // namespace vplgi
