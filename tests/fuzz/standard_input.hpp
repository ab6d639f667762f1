// SPDX-License-Identifier: MIT
#pragma once
// Standard input for one fuzz run: a file in memory that keyrot reads as it
// reads any file on its standard input (in place, or through std::cin when
// empty), made fresh for every run.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdio>
#include <iostream>

#include "check.hpp"

namespace keyrot::fuzz {

/// Standard input holds `bytes` from its start. The end-of-file and error
/// states of std::cin and of the C stream under it are cleared: a run that
/// read an empty input to its end must not leave every later input empty.
inline void set_standard_input(const char* bytes, std::size_t size) {
    static const int input = [] {
        const int fd = ::memfd_create("fuzz stdin", 0);
        require(fd >= 0 && ::dup2(fd, STDIN_FILENO) == STDIN_FILENO);
        return fd;
    }();
    require(::ftruncate(input, 0) == 0 && ::pwrite(input, bytes, size, 0) == static_cast<ssize_t>(size));
    std::clearerr(stdin);
    require(std::fseek(stdin, 0, SEEK_SET) == 0);  // also drops what the C stream buffered
    std::cin.clear();
}

}  // namespace keyrot::fuzz
