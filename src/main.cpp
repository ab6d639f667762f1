// SPDX-License-Identifier: MIT
// keyrot's entry point: parse the command line, run, map errors to status 2.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>

#include <csignal>
#include <iostream>
#include <new>
#include <sstream>

#include "app/app.hpp"
#include "cli.hpp"
#include "io/common/output.hpp"
#include "ground/warnings.hpp"
#include "keyrot/error.hpp"

namespace {

/// A standard descriptor the caller closed would be taken by the next file
/// keyrot opens (a spool file, an output's temporary file), which would
/// then get what was meant for the stream: /dev/null holds its place, and
/// the stream is marked failed, so that using it is an error.
void hold_if_closed(int fd, std::ios& stream) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) return;
    const int null = ::open("/dev/null", fd == STDIN_FILENO ? O_RDONLY : O_WRONLY);
    if (null >= 0 && null != fd) ::dup2(null, fd), ::close(null);
    stream.setstate(std::ios::badbit);
}

}  // namespace

int main(int argc, char** argv) {
    // A closed pipe (keyrot ... | head) ends keyrot quietly, as it does any
    // Unix filter, even if the parent process ignored SIGPIPE.
    std::signal(SIGPIPE, SIG_DFL);
    hold_if_closed(STDIN_FILENO, std::cin);
    hold_if_closed(STDOUT_FILENO, std::cout);
    hold_if_closed(STDERR_FILENO, std::cerr);
    try {
        std::ostringstream help;  // --help and --version, written as output is
        auto opts = keyrot::parse_command_line(argc, argv, help);
        if (!opts) {
            keyrot::write_to_stream(std::cout, help.str());
            return 0;
        }
        opts->progress = ::isatty(STDERR_FILENO) == 1;
        opts->terminal_out = ::isatty(STDOUT_FILENO) == 1;
        return keyrot::run(*opts, std::cin, std::cout, std::cerr);
    } catch (const keyrot::error& e) {
        keyrot::print_error(std::cerr, e.what());
    } catch (const std::bad_alloc&) {
        keyrot::print_error(std::cerr, "out of memory");
    } catch (const std::exception& e) {
        keyrot::print_error(std::cerr, std::string("internal error: ") + e.what());
    }
    return 2;
}
