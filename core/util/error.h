// The one runtime error type of vplgi. Messages name the thing that is wrong
// ("scenes/x.json: light 3: \"intensity\" must be >= 0"); only main() and test runners catch.
#pragma once

#include <stdexcept>
#include <string>

namespace vplgi {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws Error(message) when !condition. For checks on input, not for logic errors (use assert).
inline void require(bool condition, const std::string& message)
{
    if (!condition) throw Error(message);
}

} // namespace vplgi
