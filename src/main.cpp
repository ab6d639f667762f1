// keyrot's entry point: parse the command line, run, map errors to status 2.
#include <iostream>

#include "keyrot/app.hpp"
#include "keyrot/cli.hpp"
#include "keyrot/error.hpp"

int main(int argc, char** argv) {
    try {
        const auto opts = keyrot::parse_command_line(argc, argv, std::cout);
        if (!opts) return 0;
        return keyrot::run(*opts, std::cin, std::cout, std::cerr);
    } catch (const keyrot::error& e) {
        std::cerr << "keyrot: " << e.what() << '\n';
    } catch (const std::exception& e) {
        std::cerr << "keyrot: internal error: " << e.what() << '\n';
    }
    return 2;
}
