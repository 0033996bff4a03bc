#pragma once
// Two kinds of failure, told apart by exit status: bad input (2) and everything else (1).
#include <stdexcept>
#include <string>

namespace sl {

// Invalid command line or scene: the message names the file and the key or line at fault.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// I/O, encoder or other runtime failure.
struct RuntimeFailure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace sl
