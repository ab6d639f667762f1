// SPDX-License-Identifier: MIT
#include "cli.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <ostream>
#include <span>

#include "cli_flags.hpp"
#include "formats_help.hpp"
#include "ground/text.hpp"
#include "io/common/format.hpp"
#include "suggest.hpp"

namespace keyrot {

const char* const version = KEYROT_VERSION;

namespace {

using cli::commands;

/// CLI11's help, with one blank line between groups of flags (not two).
std::string help_text(const CLI::App& app, CLI::AppFormatMode mode = CLI::AppFormatMode::Normal,
                      const std::string& parent = "") {
    std::string text = app.help(parent, mode);
    for (auto at = text.find("\n\n\n"); at != std::string::npos; at = text.find("\n\n\n", at)) text.erase(at, 1);
    return text;
}

/// " (did you mean 'X'?)", or nothing.
std::string did_you_mean(const std::optional<std::string>& name) {
    return name ? fmt::format(" (did you mean '{}'?)", *name) : "";
}

/// "a", "a or b", "a, b or c".
std::string spoken_list(const std::vector<std::string>& names, std::string_view conjunction) {
    if (names.size() < 2) return names.empty() ? "" : names.front();
    return fmt::format("{} {} {}", fmt::join(names.begin(), names.end() - 1, ", "), conjunction, names.back());
}

/// A command's flags as typed: --fps, -o; not --help.
std::vector<std::string> flags_of(const CLI::App& sub) {
    std::vector<std::string> flags;
    for (const CLI::Option* option : sub.get_options()) {
        for (const std::string& name : option->get_lnames())
            if (name != "help") flags.push_back("--" + name);
        for (const std::string& name : option->get_snames())
            if (name != "h") flags.push_back("-" + name);
    }
    return flags;
}

/// The words of CLI11's "The following arguments were not expected: 0.5 --fsp".
std::vector<std::string_view> unexpected_words(std::string_view message) {
    std::vector<std::string_view> words;
    const auto colon = message.rfind(": ");
    if (colon == std::string_view::npos) return words;
    for (std::string_view rest = message.substr(colon + 2); !rest.empty();) {
        const auto space = std::min(rest.find(' '), rest.size());
        if (space > 0) words.push_back(rest.substr(0, space));
        rest.remove_prefix(std::min(space + 1, rest.size()));
    }
    return words;
}

/// For slerp's parameters given without -t (keyrot slerp Q0 Q1 0.5 0.25):
/// " (did you mean '-t 0.25 0.5'?)", in increasing order (CLI11 lists
/// them in an order of its own).
std::string parameter_suggestion(std::vector<std::string_view> unexpected) {
    const auto number = [](std::string_view w) { return parse_number(w).has_value(); };
    if (unexpected.empty() || !std::ranges::all_of(unexpected, number)) return "";
    std::ranges::stable_sort(unexpected, {}, [](std::string_view w) { return *parse_number(w); });
    return did_you_mean(fmt::format("-t {}", fmt::join(unexpected, " ")));
}

/// Flags that name the same choice in other commands: the format of
/// compare's report is its --report, that of info's its --to.
struct same_choice {
    std::string_view command, typed, own;
};
constexpr std::array<same_choice, 2> same_choices{{{"compare", "--to", "--report"}, {"info", "--report", "--to"}}};

/// For an unexpected flag (CLI11's "The following argument was not
/// expected: --fsp"): " (did you mean '--fps'?)" when likely_meant finds
/// one of the command's flags. A flag of other commands names them, as
/// typed or as likely meant: reduce's "--fps" gives " (--fps is a flag of
/// keyrot resample)", resample's "--tolerance" gives " (did you mean
/// '--tol' of keyrot compare or reduce?)", not resample's "--to"; and
/// compare's "--to" gives " (--to is a flag of keyrot ...; did you mean
/// '--report'?)", the flag of the same choice.
std::string flag_suggestion(std::string_view command_name, const std::vector<std::string_view>& unexpected) {
    const auto typed = std::ranges::find_if(unexpected, [](std::string_view w) { return w.starts_with("-"); });
    if (typed == unexpected.end()) return "";
    const std::string word(typed->substr(0, typed->find('=')));
    // Every command defined (only the one named was, for start-up), to see
    // whose flags these are.
    CLI::App all;
    options unused;
    cli::raw_flags unused_flags;
    std::vector<std::string> own;
    std::map<std::string, std::vector<std::string>> others;  // a flag of other commands: theirs
    for (const auto& c : commands) {
        CLI::App* sub = all.add_subcommand(c.name);
        c.define(*sub, unused, unused_flags);
        for (std::string& flag : flags_of(*sub)) {
            if (command_name == c.name) own.push_back(std::move(flag));
            else others[std::move(flag)].emplace_back(c.name);
        }
    }
    for (const std::string& flag : own) others.erase(flag);
    const auto owners = [&](const std::string& flag, std::string_view conjunction) {
        return "keyrot " + spoken_list(others.at(flag), conjunction);
    };
    if (others.contains(word)) {
        const auto same = std::ranges::find_if(
            same_choices, [&](const same_choice& c) { return c.command == command_name && c.typed == word; });
        const std::string hint = same == same_choices.end() ? "" : fmt::format("; did you mean '{}'?", same->own);
        return fmt::format(" ({} is a flag of {}{})", word, owners(word, "and"), hint);
    }
    std::vector<std::string> names = own;
    for (const auto& entry : others) names.push_back(entry.first);
    const std::size_t letters = word.size() - std::min(word.find_first_not_of('-'), word.size());
    // (a slip as near one of the command's flags as another's: the command's)
    std::optional<std::string> meant = likely_meant(word, names, letters);
    if (!meant) meant = likely_meant(word, own, letters);
    if (meant && others.contains(*meant))
        return fmt::format(" (did you mean '{}' of {}?)", *meant, owners(*meant, "or"));
    return did_you_mean(meant);
}

/// For a value not among a flag's choices (CLI11's "--rep: quaternion not
/// in {axis-angle,quat,...}"), " (did you mean 'quat'?)" when likely_meant
/// finds one; a file's extension means its format ("jsonl": "ndjson").
std::string choice_suggestion(const std::string& message) {
    const auto set = message.rfind(" not in {");
    if (set == std::string::npos || !message.ends_with("}")) return "";
    const auto colon = message.rfind(": ", set);
    const std::size_t start = colon == std::string::npos ? 0 : colon + 2;
    const std::string word = message.substr(start, set - start);
    std::vector<std::string> choices;
    std::string_view list = std::string_view(message).substr(set + 9);
    list.remove_suffix(1);
    for (std::size_t comma; !list.empty(); list.remove_prefix(std::min(comma + 1, list.size()))) {
        comma = std::min(list.find(','), list.size());
        choices.emplace_back(list.substr(0, comma));
    }
    if (const auto f = format_of_path("." + word); f && std::ranges::find(choices, to_string(*f)) != choices.end())
        return did_you_mean(std::string(to_string(*f)));
    return did_you_mean(likely_meant(word, choices, word.size()));
}

std::vector<std::string> command_names() {
    std::vector<std::string> names;
    for (const auto& c : commands) names.emplace_back(c.name);
    return names;
}

/// The commands as a message lists them: "resample, convert, slerp, compare, info, reduce or plot".
std::string listed_commands() {
    return spoken_list(command_names(), "or");
}

/// `keyrot help [TOPIC]`: the program's help, a command's, or the formats'.
void print_help_topic(const CLI::App& app, std::span<CLI::App* const> subs, int argc, const char* const* argv,
                      std::ostream& out) {
    if (argc > 3) throw usage_error(fmt::format("help: expected one topic, got '{}' too", excerpt(argv[3])));
    const std::string_view topic = argc == 3 ? argv[2] : "";
    if (topic.empty()) {
        out << help_text(app);
        return;
    }
    if (topic == "formats") {
        out << formats_help();
        return;
    }
    for (std::size_t i = 0; i < commands.size(); ++i)
        if (topic == commands[i].name) {
            out << help_text(*subs[i], CLI::AppFormatMode::Normal, app.get_name());
            return;
        }
    std::vector<std::string> topics = command_names();
    topics.emplace_back("formats");
    throw usage_error(fmt::format("help: unknown topic '{}': expected formats, {} (did you mean '{}'?)", excerpt(topic),
                                  listed_commands(), nearest(topic, topics)));
}

}  // namespace

std::optional<options> parse_command_line(int argc, const char* const* argv, std::ostream& out) {
    if (argc == 2 && std::string_view(argv[1]) == "--version") {
        // Before CLI11, which says it by throwing: a static binary's first
        // exception sorts the unwind tables, a millisecond.
        out << "keyrot " << version << '\n';
        return std::nullopt;
    }
    CLI::App app{"keyrot: keyframe rotation interpolator", "keyrot"};
    app.set_version_flag("--version", version);
    app.require_subcommand(1);
    app.footer(R"(Run 'keyrot COMMAND --help' for a command's flags and examples, 'keyrot help formats' for the CSV
columns and JSON fields a file needs.

Exit status: 0 success, 1 compare found differences, 2 invalid input or usage (one line on standard error).)");
    options o;
    cli::raw_flags f;
    // Only the command named first is defined: each command and option is
    // CLI11 allocations at every start-up. Anything else defines all, for
    // --help and for the error message.
    const std::string_view first = argc > 1 ? argv[1] : "";
    const bool known = std::any_of(commands.begin(), commands.end(), [&](const auto& c) { return first == c.name; });
    if (!known && !first.empty() && first.front() != '-' && first != "help") {
        std::vector<std::string> names = command_names();
        names.emplace_back("help");
        throw usage_error(fmt::format("unknown command '{}': expected {} (did you mean '{}'?)", excerpt(first),
                                      listed_commands(), nearest(first, names)));
    }
    std::array<CLI::App*, std::tuple_size_v<decltype(commands)>> subs{};
    for (std::size_t i = 0; i < commands.size(); ++i) {
        if (known && first != commands[i].name) continue;
        subs[i] = app.add_subcommand(commands[i].name, commands[i].description);
        commands[i].define(*subs[i], o, f);
    }
    if (!known) app.add_subcommand("help", "help on a command, or on the formats: keyrot help formats");
    if (first == "help") {
        print_help_topic(app, subs, argc, argv, out);
        return std::nullopt;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        out << help_text(app);
        return std::nullopt;
    } catch (const CLI::CallForAllHelp&) {
        out << help_text(app, CLI::AppFormatMode::All);
        return std::nullopt;
    } catch (const CLI::CallForVersion&) {
        out << "keyrot " << version << '\n';
        return std::nullopt;
    } catch (const CLI::ParseError& e) {
        if (!known) throw usage_error(fmt::format("expected a command: {} (see keyrot --help)", listed_commands()));
        std::string what = e.what();
        if (what == "KEY is required") what = "KEY and ANSWER are missing: expected the key, then one answer or more";
        if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
            const std::vector<std::string_view> unexpected = unexpected_words(what);
            const std::string parameter = first == "slerp" ? parameter_suggestion(unexpected) : "";
            what += parameter.empty() ? flag_suggestion(first, unexpected) : parameter;
        }
        if (dynamic_cast<const CLI::ValidationError*>(&e)) what += choice_suggestion(what);
        throw usage_error(fmt::format("{}: {} (see keyrot {} --help)", first, what, first));
    }
    for (std::size_t i = 0; i < commands.size(); ++i)
        if (subs[i] && subs[i]->parsed()) o.cmd = commands[i].cmd;
    cli::finish(o, f);
    if (o.cmd == command::compare || o.cmd == command::reduce)
        for (const auto& [flag, tol] : {std::pair("--tol", o.tol_deg), std::pair("--tol-translation", o.tol_translation),
                                        std::pair("--tol-velocity", o.tol_velocity.value_or(0)),
                                        std::pair("--tol-acceleration", o.tol_acceleration.value_or(0))})
            if (!(std::isfinite(tol) && tol >= 0))
                throw usage_error(fmt::format("{}: expected a tolerance of 0 or more, got {}", flag, tol));
    if (o.cmd == command::reduce && o.report && !o.output && !o.output_dir)
        throw usage_error("--report json: the report takes standard output: expected -o FILE or --output-dir DIR for "
                          "the keys");
    return o;
}

}  // namespace keyrot
