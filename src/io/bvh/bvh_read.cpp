// SPDX-License-Identifier: MIT
#include "io/bvh/bvh_read.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <set>

#include "ground/text.hpp"
#include "io/bvh/column_store.hpp"
#include "io/common/line_reader.hpp"

namespace keyrot {
namespace {

/// The words of a line, split at spaces and tabs.
std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (true) {
        i = line.find_first_not_of(" \t", i);
        if (i == std::string_view::npos) return out;
        const std::size_t end = std::min(line.find_first_of(" \t", i), line.size());
        out.push_back(line.substr(i, end - i));
        i = end;
    }
}

bool is(std::string_view word, std::string_view keyword) { return ascii_lower(word) == ascii_lower(keyword); }

/// 0..2: X/Y/Z position, 3..5: X/Y/Z rotation; -1 for another name.
int channel_kind(std::string_view name) {
    const std::string n = ascii_lower(name);
    if (n.size() != 9 || (n[0] != 'x' && n[0] != 'y' && n[0] != 'z')) return -1;
    const int axis = n[0] - 'x';
    if (n.substr(1) == "position") return axis;
    if (n.substr(1) == "rotation") return 3 + axis;
    return -1;
}

/// The rate of a Frame Time as written: the one whole number of frames per
/// second whose frame time, rounded to the decimals written, is the one
/// written (0.0083333 is 120 fps); else, where there is none or more than
/// one (0.017 is the rounding of both 1/58 and 1/59), its reciprocal.
double rate_of(std::string_view written, double frame_time) {
    const double exact = 1 / frame_time;
    const auto point = written.find('.');
    if (point == std::string_view::npos || written.find_first_of("eE") != std::string_view::npos) return exact;
    const double half_digit = 0.5 * std::pow(10.0, -static_cast<int>(written.size() - point - 1)) * (1 + 1e-9);
    const auto rounds_to_it = [&](double rate) { return rate >= 1 && std::fabs(1 / rate - frame_time) <= half_digit; };
    const double whole = std::round(exact);
    return rounds_to_it(whole) && !rounds_to_it(whole - 1) && !rounds_to_it(whole + 1) ? whole : exact;
}

/// Reads the hierarchy and the motion's header from `lines`, which then
/// stand at the first frame line.
class header_parser {
public:
    header_parser(line_reader& lines, const std::string& source) : lines_(lines), source_(source) {}

    bvh_source parse() {
        std::string_view line;
        bool started = false;
        while (lines_.next(line)) {
            const auto w = words(line);
            if (w.empty()) {
                keep(line);
                continue;
            }
            if (!started) {
                if (!is(w[0], "HIERARCHY") || w.size() != 1)
                    fail(fmt::format("'{}': expected HIERARCHY, the start of a BVH file", excerpt(trim(line))));
                started = true;
                keep(line);
                continue;
            }
            if (is(w[0], "MOTION")) {
                if (expect_brace_) fail("MOTION: expected '{'");
                if (!open_.empty()) fail(fmt::format("MOTION inside '{}': expected its '}}' first", block_name()));
                if (out_.joints.empty() && !roots_) fail("MOTION before any ROOT: expected a joint hierarchy");
                motion_header();
                return std::move(out_);
            }
            for (std::size_t i = 0; i < w.size(); ++i) i = word(w, i);
            keep(line);
        }
        fail(started ? "no MOTION section: expected MOTION, Frames and Frame Time after the hierarchy"
                     : "no HIERARCHY: expected a BVH file");
    }

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw input_error(where(source_, lines_.number()), what);
    }

    /// A ROOT, JOINT or End Site, the child of the open block; the next '{' opens it.
    void add_node(std::string name) {
        out_.nodes.push_back({std::move(name), open_.empty() ? std::nullopt : std::optional(open_.back()), {}, {}});
        expect_brace_ = true;
    }

    const std::string& block_name() const { return out_.nodes[open_.back()].name; }

    void keep(std::string_view line) {
        out_.hierarchy.append(line);
        out_.hierarchy += lines_.crlf() ? "\r\n" : "\n";
        if (lines_.crlf()) out_.newline = "\r\n";
    }

    /// The word at w[i] and those it takes; returns the index of the last one taken.
    std::size_t word(const std::vector<std::string_view>& w, std::size_t i) {
        const std::string_view k = w[i];
        if (k == "{") {
            if (!expect_brace_) fail("'{' without ROOT, JOINT or End Site before it");
            expect_brace_ = false;
            open_.push_back(out_.nodes.size() - 1);
            return i;
        }
        if (expect_brace_) fail(fmt::format("'{}': expected '{{'", excerpt(k)));
        if (k == "}") {
            if (open_.empty()) fail("'}' without a matching '{'");
            open_.pop_back();
            in_joint_ = false;
            return i;
        }
        if (is(k, "ROOT") || is(k, "JOINT")) {
            const bool root = is(k, "ROOT");
            if (root != open_.empty())
                fail(root ? "ROOT inside a joint: expected JOINT" : "JOINT outside a ROOT: expected ROOT first");
            std::size_t end = i + 1;
            while (end < w.size() && w[end] != "{") ++end;
            if (end == i + 1) fail(fmt::format("{} without a name: expected a joint name", k));
            const std::string name(w[i + 1].data(), static_cast<std::size_t>(w[end - 1].end() - w[i + 1].begin()));
            check_track_name(name, where(source_, lines_.number()));
            add_node(name);
            // Two joints of one name are two tracks: the second is "<name>.2".
            const std::string track = distinct_track_name(name, names_);
            joint_ = {track, lines_.number(), {}, {}, {}, false};
            in_joint_ = true;
            roots_ += root;
            return end - 1;
        }
        if (is(k, "End")) {
            if (open_.empty()) fail("End Site outside a joint");
            if (i + 1 == w.size() || !is(w[i + 1], "Site")) fail("'End': expected 'End Site'");
            add_node(out_.nodes[open_.back()].name + "_End");
            in_joint_ = false;
            return i + 1;
        }
        if (open_.empty()) fail(fmt::format("'{}' outside a joint: expected ROOT", excerpt(k)));
        if (is(k, "OFFSET")) {
            if (i + 3 >= w.size()) fail("OFFSET: expected three numbers");
            double xyz[3];
            for (std::size_t j = 1; j <= 3; ++j) {
                const auto v = parse_number(w[i + j]);
                if (!v) fail(fmt::format("OFFSET: '{}': expected a number", excerpt(w[i + j])));
                xyz[j - 1] = *v;
            }
            out_.nodes[open_.back()].offset = {xyz[0], xyz[1], xyz[2]};
            return i + 3;
        }
        if (is(k, "CHANNELS")) return channels(w, i);
        fail(fmt::format("'{}': expected ROOT, JOINT, End Site, OFFSET, CHANNELS, a brace or MOTION", excerpt(k)));
    }

    std::size_t channels(const std::vector<std::string_view>& w, std::size_t i) {
        if (!in_joint_) fail("CHANNELS outside a joint: expected them in ROOT or JOINT, before its children");
        if (joint_.line == 0) fail(fmt::format("joint '{}' has CHANNELS twice: expected them once", block_name()));
        const auto count = i + 1 < w.size() ? parse_number(w[i + 1]) : std::nullopt;
        if (!count || *count < 0 || *count != std::floor(*count) || *count > 6)
            fail("CHANNELS: expected a count from 0 to 6, then the channel names");
        const auto n = static_cast<std::size_t>(*count);
        if (w.size() - i - 2 != n)
            fail(fmt::format("CHANNELS {}: expected {} channel names on the line, got {}", n, n, w.size() - i - 2));
        std::string order;
        std::set<int> seen;
        for (std::size_t j = 0; j < n; ++j) {
            const std::string_view name = w[i + 2 + j];
            const int kind = channel_kind(name);
            if (kind < 0)
                fail(
                    fmt::format("channel '{}': expected Xposition, Yposition, Zposition, Xrotation, Yrotation or "
                                "Zrotation",
                                excerpt(name)));
            if (!seen.insert(kind).second) fail(fmt::format("channel {} listed twice: expected each once", name));
            joint_.channels.emplace_back(name);
            joint_.kinds.push_back(kind);
            if (kind >= 3)
                order += static_cast<char>('X' + kind - 3);
            else
                joint_.positions = true;
        }
        for (const char axis : {'X', 'Y', 'Z'})
            if (order.find(axis) == std::string::npos) order += axis;
        joint_.euler = *parse_euler_seq(order);
        if (n > 0) {
            out_.nodes[open_.back()].joint = out_.joints.size();
            out_.joints.push_back(joint_);
        }
        joint_.line = 0;  // CHANNELS given
        return i + 1 + n;
    }

    void motion_header() {
        std::string_view line;
        const auto next_words = [&](std::string_view what) {
            while (lines_.next(line))
                if (auto w = words(line); !w.empty()) return w;
            fail(fmt::format("no '{}' line: expected it after MOTION", what));
        };
        auto w = next_words("Frames:");
        const auto frames = w.size() == 2 && is(w[0], "Frames:") ? parse_number(w[1]) : std::nullopt;
        if (!frames || *frames < 0 || *frames != std::floor(*frames) || *frames > 9e15)
            fail(fmt::format("'{}': expected 'Frames: N', the number of frame lines", excerpt(trim(line))));
        out_.frames = static_cast<std::size_t>(*frames);
        w = next_words("Frame Time:");
        const auto time = w.size() == 3 && is(w[0], "Frame") && is(w[1], "Time:") ? parse_number(w[2]) : std::nullopt;
        if (!time) fail(fmt::format("'{}': expected 'Frame Time: T', seconds per frame", excerpt(trim(line))));
        if (!(*time > 0)) fail(fmt::format("Frame Time {}: expected a positive number of seconds", w[2]));
        out_.frame_time = *time;
        out_.frame_time_text = w[2];
        out_.fps = rate_of(w[2], *time);
        if (!std::isfinite(out_.fps)) fail(fmt::format("Frame Time {}: expected at most a frame a nanosecond", w[2]));
    }

    line_reader& lines_;
    const std::string& source_;
    bvh_source out_{{}, "\n", {}, {}, 0, {}, 0, 0};
    std::vector<std::size_t> open_;  // the open blocks, as indices into out_.nodes
    std::set<std::string> names_;    // the tracks' names so far
    bool expect_brace_ = false, in_joint_ = false;
    bvh_joint joint_;
    int roots_ = 0;
};

/// A BVH file's frame lines after its header, a line of numbers at a time.
class bvh_frames {
public:
    bvh_frames(std::istream& in, const read_options& ro) : source_(ro.source), lines_(in, ro.max_line_bytes, ro.source) {
        header_ = header_parser(lines_, ro.source).parse();
        for (const bvh_joint& j : header_.joints) width_ += j.channels.size();
        if (width_ == 0) throw input_error(source_, "no joint has CHANNELS: expected some channels to read");
        settings_ = ro.settings;
        settings_.angles = angle_unit::degrees;
        settings_.key_fps = header_.fps;
        settings_.key_fps_given = false;
        settings_.interpolation = std::nullopt;
    }

    const bvh_source& header() const { return header_; }
    std::size_t width() const { return width_; }
    std::size_t line() const { return lines_.number(); }
    /// The flags' settings, with the joint `j`'s sequence, degrees and the file's rate.
    const key_settings& settings(std::size_t j) {
        settings_.euler = header_.joints[j].euler;
        return settings_;
    }

    /// The values of the next frame line into `row` (width() of them);
    /// false after the last, once their count is checked against 'Frames:'.
    bool read(double* row) {
        if (at_end_) return false;
        std::string_view line;
        while (lines_.next(line)) {
            const char* p = line.data();
            const char* const end = p + line.size();
            const auto blank = [&] {
                while (p != end && (*p == ' ' || *p == '\t')) ++p;
            };
            blank();
            if (p == end) continue;
            const auto where = [&] { return keyrot::where(source_, lines_.number()); };
            if (read_ == header_.frames)
                throw input_error(where(), fmt::format("a frame line after the {} that 'Frames:' states: expected {}",
                                                       header_.frames, header_.frames));
            std::size_t n = 0;
            for (; p != end; ++n) {
                const char* const start = p;
                while (p != end && *p != ' ' && *p != '\t') ++p;
                const std::string_view word(start, static_cast<std::size_t>(p - start));
                // from_chars at once for the common number; parse_number for the rest ('+', underflow, errors).
                double v = 0;
                const auto [stop, ec] = std::from_chars(start, p, v);
                if (ec != std::errc{} || stop != p || !std::isfinite(v)) {
                    const auto parsed = parse_number(word);
                    if (!parsed)
                        throw input_error(where(),
                                          fmt::format("value {}: '{}': expected a number", n + 1, excerpt(word)));
                    v = *parsed;
                }
                if (n < width_) row[n] = v;
                blank();
            }
            if (n != width_)
                throw input_error(where(),
                                  fmt::format("expected {} values (the hierarchy's channels), got {}", width_, n));
            ++read_;
            return true;
        }
        at_end_ = true;
        if (read_ != header_.frames)
            throw input_error(
                where(source_, lines_.number()),
                fmt::format("'Frames: {}', but {} frame lines: expected as many", header_.frames, read_));
        if (read_ == 0) throw input_error(source_, "'Frames: 0': expected at least one frame");
        return false;
    }

    /// Key `frame` of joint `j`, at `line`, whose channel `c` has the value `value(c)`.
    template <typename Value>
    void key_of(std::size_t j, std::size_t frame, std::size_t line, Value value, raw_key& k) const {
        const bvh_joint& joint = header_.joints[j];
        k.reset();
        k.at.line = line;
        k.frame = static_cast<double>(frame);
        k.kind = rep::euler;
        std::size_t angle = 0;
        vec3 position{};
        for (std::size_t c = 0; c < joint.kinds.size(); ++c) {
            const int kind = joint.kinds[c];
            const double v = value(c);
            if (kind >= 3)
                k.values[angle++] = v;
            else
                (kind == 0 ? position.x : kind == 1 ? position.y : position.z) = v;
        }
        if (joint.positions) k.translation = position;
    }

private:
    std::string source_;
    line_reader lines_;
    bvh_source header_;
    std::size_t width_ = 0;  // values per frame
    key_settings settings_;
    std::size_t read_ = 0;  // frame lines read
    bool at_end_ = false;
};

/// Each frame's line number, held as the first frame's and the places
/// where blank lines shift the rest (none, in most files): a long take's
/// line numbers would otherwise grow with it.
class frame_lines {
public:
    void push_back(std::size_t line) {
        const std::size_t frame = count_++;
        if (frame == 0) first_ = line;
        else if (line != first_ + frame + shift()) shifts_.emplace_back(frame, line - first_ - frame);
    }
    std::size_t size() const noexcept { return count_; }
    std::size_t operator[](std::size_t frame) const {
        const auto after = std::upper_bound(shifts_.begin(), shifts_.end(), frame,
                                            [](std::size_t f, const auto& s) { return f < s.first; });
        return first_ + frame + (after == shifts_.begin() ? 0 : std::prev(after)->second);
    }

private:
    std::size_t shift() const noexcept { return shifts_.empty() ? 0 : shifts_.back().second; }
    std::size_t first_ = 0, count_ = 0;
    std::vector<std::pair<std::size_t, std::size_t>> shifts_;  // (first frame shifted, lines skipped before it)
};

/// A BVH file's keys joint after joint: the frames read whole into a column
/// of numbers per channel (a frame-major file gives its joints' keys one
/// joint after another), kept in a temporary file.
class bvh_keys final : public key_reader {
public:
    bvh_keys(std::istream& in, const read_options& ro)
        : frames_(in, ro), columns_(frames_.width(), frames_.header().frames) {
        row_.resize(frames_.width());
    }

    bool next(std::string& track, raw_key& k) override {
        const bvh_source& h = frames_.header();
        if (joint_ == h.joints.size()) return false;
        // The first joint's keys come as their lines are read (a caller that
        // wants only the first key reads one line); its last reads the rest.
        read_lines(joint_ == 0 && frame_ + 1 < h.frames ? frame_ + 1 : SIZE_MAX);
        track = h.joints[joint_].name;
        settings_ = &frames_.settings(joint_);
        frames_.key_of(joint_, frame_, frame_lines_[frame_], [&](std::size_t c) { return columns_.at(column_ + c, frame_); },
                       k);
        if (++frame_ == h.frames) frame_ = 0, column_ += h.joints[joint_].channels.size(), ++joint_;
        return true;
    }
    bool named() const override { return true; }
    location start() const override { return {}; }
    const key_settings& settings() const override { return *settings_; }

private:
    /// Reads frame lines until `count` frames are in (SIZE_MAX: all of them).
    void read_lines(std::size_t count) {
        while (frame_lines_.size() < count && frames_.read(row_.data())) {
            columns_.push(row_.data());
            frame_lines_.push_back(frames_.line());
        }
    }

    bvh_frames frames_;
    column_store columns_;                    // per channel, frame after frame
    std::vector<double> row_;                 // the line being read
    frame_lines frame_lines_;                 // each frame's line
    const key_settings* settings_ = nullptr;
    std::size_t joint_ = 0, column_ = 0, frame_ = 0;
};

}  // namespace

std::unique_ptr<key_reader> make_bvh_reader(std::istream& in, const read_options& ro) {
    return std::make_unique<bvh_keys>(in, ro);
}

std::shared_ptr<bvh_source> read_bvh_source(std::istream& in, const read_options& ro) {
    line_reader lines(in, ro.max_line_bytes, ro.source);
    return std::make_shared<bvh_source>(header_parser(lines, ro.source).parse());
}

}  // namespace keyrot
