// SPDX-License-Identifier: MIT
#pragma once
// A command run in-process on a fuzz input given as its standard input: a
// file in memory that keyrot reads as it reads any file on its standard
// input (in place, or through std::cin when empty), made fresh for every
// run.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "app/app.hpp"
#include "check.hpp"

namespace keyrot::fuzz {

/// Standard input holds `bytes` from its start. The end-of-file and error
/// states of std::cin and of the C stream under it are cleared: a run that
/// read an empty input to its end must not leave every later input empty.
inline void set_standard_input(std::string_view bytes) {
    static const int input = [] {
        const int fd = ::memfd_create("fuzz stdin", 0);
        require(fd >= 0 && ::dup2(fd, STDIN_FILENO) == STDIN_FILENO);
        return fd;
    }();
    require(::ftruncate(input, 0) == 0 &&
            ::pwrite(input, bytes.data(), bytes.size(), 0) == static_cast<ssize_t>(bytes.size()));
    std::clearerr(stdin);
    require(std::fseek(stdin, 0, SEEK_SET) == 0);  // also drops what the C stream buffered
    std::cin.clear();
}

/// What a command run on `input` did: its exit status, or none for flags
/// that make no command line (its usage error in `refused`); what it wrote;
/// its messages, each checked to be one printable "keyrot: " line.
struct command_run {
    std::optional<int> status;
    std::string out, err, refused;
};

inline command_run run_command(const options& o, std::string_view input) {
    set_standard_input(input);
    std::ostringstream out, err;
    command_run r;
    try {
        r.status = run(o, std::cin, out, err);
    } catch (const usage_error& e) {
        r.refused = e.what();
    }
    r.out = out.str(), r.err = err.str();
    check_output(r.err);
    return r;
}

}  // namespace keyrot::fuzz
