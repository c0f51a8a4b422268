// Measured values that the README quotes are printed on every run, passing or not (INFO shows only
// on failure), so `ctest -L numbers --verbose` lists them all. Tests that print them carry the Catch2
// tag [numbers], which tests/CMakeLists.txt turns into the ctest label "numbers".
#pragma once

#include <iostream>
#include <sstream>
#include <string>

namespace vplgi::test {

// One line "measured: <text>" on stdout.
inline void printMeasured(const std::string& text)
{
    std::cout << "measured: " << text << std::endl;
}

} // namespace vplgi::test

// MEASURED("worst relative error " << worst): streams like INFO, prints like printMeasured.
#define MEASURED(message)                                                                                            \
    do {                                                                                                             \
        std::ostringstream measuredStream_;                                                                          \
        measuredStream_ << message;                                                                                  \
        ::vplgi::test::printMeasured(measuredStream_.str());                                                         \
    } while (false)
