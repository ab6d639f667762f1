// SPDX-License-Identifier: MIT
#include "app/output_names.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <map>
#include <optional>
#include <utility>

#include "io/common/source.hpp"
#include "keyrot/error.hpp"

namespace keyrot::detail {

std::filesystem::path in_output_dir(const std::string& dir, const std::string& name, format out) {
    std::filesystem::path file = std::filesystem::path(name).filename();
    file.replace_extension(to_string(out));
    return std::filesystem::path(dir) / file;
}

void check_output_names(const options& o, const std::vector<std::string>& inputs) {
    const auto file_id = [](const std::string& path) -> std::optional<std::pair<dev_t, ino_t>> {
        struct stat st {};
        if (::stat(path.c_str(), &st) != 0) return std::nullopt;
        return std::pair(st.st_dev, st.st_ino);
    };
    std::map<std::pair<dev_t, ino_t>, std::string> input_files;
    for (const std::string& name : inputs)
        if (const auto id = is_standard_stream(name) ? std::nullopt : file_id(name)) input_files.emplace(*id, name);
    // By the output's name without its extension: the inputs, with their output's extension ("*": not known).
    std::map<std::string, std::vector<std::pair<std::string, std::string>>> by_stem;
    for (const std::string& name : inputs) {
        const std::optional<format> out = o.to ? o.to : o.from ? o.from : format_of_path(name);
        const std::filesystem::path target = in_output_dir(*o.output_dir, name, out.value_or(format::csv));
        const std::string extension = out ? std::string(to_string(*out)) : "*";
        auto& same_stem = by_stem[std::filesystem::path(target).replace_extension().string()];
        for (const auto& [other, other_extension] : same_stem)
            if (other_extension == extension || extension == "*" || other_extension == "*")
                throw usage_error(fmt::format("--output-dir {}: '{}' and '{}' would both be written to '{}': expected "
                                              "inputs with distinct names",
                                              *o.output_dir, other, name,
                                              std::filesystem::path(target).replace_extension(extension).string()));
        same_stem.emplace_back(name, extension);
        const auto id = out ? file_id(target.string()) : std::nullopt;
        if (const auto input = id ? input_files.find(*id) : input_files.end(); input != input_files.end())
            throw usage_error(fmt::format("--output-dir {}: the output of '{}' would replace the input '{}'",
                                          *o.output_dir, name, input->second));
    }
}

}  // namespace keyrot::detail
