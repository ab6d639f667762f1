// keyrot's entry point: parse the command line, run, map errors to status 2.
#include <unistd.h>

#include <csignal>
#include <iostream>
#include <new>

#include "keyrot/app.hpp"
#include "keyrot/cli.hpp"
#include "keyrot/error.hpp"

int main(int argc, char** argv) {
    // A closed pipe (keyrot ... | head) ends keyrot quietly, as it does any
    // Unix filter, even if the parent process ignored SIGPIPE.
    std::signal(SIGPIPE, SIG_DFL);
    try {
        auto opts = keyrot::parse_command_line(argc, argv, std::cout);
        if (!opts) return 0;
        opts->progress = ::isatty(STDERR_FILENO) == 1;
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
