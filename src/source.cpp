#include "keyrot/source.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "keyrot/error.hpp"

namespace keyrot {

input_source::input_source(const std::string& name, std::istream& stdin_stream)
    : name_(name), source_(name == "-" ? "<stdin>" : name), path_(name) {
    if (name != "-") {
        std::error_code ec;
        if (std::filesystem::is_directory(name, ec)) throw error(fmt::format("cannot read '{}': it is a directory", name));
        if (!std::ifstream(name, std::ios::binary)) throw error(fmt::format("cannot read '{}': {}", name, std::strerror(errno)));
        return;
    }
    // Standard input goes to a temporary file (not memory), which is removed
    // when the source is done with.
    path_ = (std::filesystem::temp_directory_path() / "keyrot-stdin-XXXXXX").string();
    const int fd = ::mkstemp(path_.data());
    if (fd < 0) throw error(fmt::format("cannot store standard input in '{}': {}", path_, std::strerror(errno)));
    ::close(fd);
    temporary_ = true;
    std::ofstream copy(path_, std::ios::binary);
    copy << stdin_stream.rdbuf();
    copy.flush();
    if (!copy) throw error(fmt::format("cannot store standard input in '{}': {}", path_, std::strerror(errno)));
}

input_source::~input_source() {
    if (temporary_) std::remove(path_.c_str());
}

std::unique_ptr<std::istream> input_source::open() const {
    auto in = std::make_unique<std::ifstream>(path_, std::ios::binary);
    if (!*in) throw error(fmt::format("cannot read '{}': {}", source_, std::strerror(errno)));
    return in;
}

format input_source::detect(std::optional<format> given) const {
    if (given) return *given;
    if (name_ != "-")
        if (auto by_name = format_of_path(name_)) return *by_name;
    // The first 64 KiB decide (sniff_format needs the first line).
    std::string start(std::size_t{1} << 16, '\0');
    const auto in = open();
    in->read(start.data(), static_cast<std::streamsize>(start.size()));
    start.resize(static_cast<std::size_t>(in->gcount()));
    return sniff_format(start);
}

}  // namespace keyrot
