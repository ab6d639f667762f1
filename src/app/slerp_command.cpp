// SPDX-License-Identifier: MIT
// slerp: two rotations interpolated at the parameters asked, as a table.
#include <fmt/format.h>

#include <algorithm>
#include <ostream>
#include <string_view>

#include "app/commands.hpp"
#include "app/plan.hpp"
#include "ground/text.hpp"
#include "io/common/layout.hpp"
#include "io/open.hpp"

namespace keyrot::detail {

namespace {

/// A slerp operand ("0,0,0.7071,0.7071") as a key at `time`.
raw_key operand(const char* name, const std::string& text, const options& o, double time) {
    raw_key k;
    k.time = time;
    k.kind = o.from_rep;
    const std::size_t want = o.from_rep == rep::rotvec || o.from_rep == rep::euler ? 3 : 4;
    std::vector<double> values;
    std::string_view rest = text;
    while (true) {
        const auto comma = rest.find(',');
        const auto v = parse_number(rest.substr(0, comma));
        if (!v) break;
        values.push_back(*v);
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
        if (values.size() > want) break;
    }
    const bool complete = values.size() == want && (rest.find(',') == std::string_view::npos);
    if (!complete) {
        const char* what = o.from_rep == rep::quat         ? (o.order == quat_order::wxyz ? "w,x,y,z" : "x,y,z,w")
                           : o.from_rep == rep::axis_angle ? "ax,ay,az,angle"
                           : o.from_rep == rep::rotvec     ? "rx,ry,rz"
                                                           : "e1,e2,e3";
        throw usage_error(fmt::format("{}: expected {} comma-separated numbers ({}, --from-rep {}), got '{}'", name, want,
                                      what, to_string(o.from_rep), excerpt(text)));
    }
    if (o.from_rep == rep::quat) {
        const auto wxyz = from_quat_order({values[0], values[1], values[2], values[3]}, o.order);
        std::copy(wxyz.begin(), wxyz.end(), k.values.begin());
    } else {
        std::copy(values.begin(), values.end(), k.values.begin());
    }
    return k;
}

}  // namespace

int run_slerp(const options& o, std::ostream& out, std::ostream& err) {
    const method how = o.how.value_or(method::slerp);
    if (how == method::squad) throw usage_error("--method squad needs more than two keys: use resample");
    if (o.steps) {
        if (*o.steps < 1) throw usage_error(fmt::format("--steps: expected at least 1, got {}", *o.steps));
        // A mistyped count must not write for hours.
        if (*o.steps + 1.0 > o.max_frames)
            throw usage_error(fmt::format("--steps {} makes {} rows: expected at most {:g} (--max-frames N raises the limit)",
                                          *o.steps, *o.steps + 1.0, o.max_frames));
    }
    if (o.ts.empty() && !o.steps) throw usage_error("slerp needs -t T or --steps N");
    // Each operand is its own source for messages: "keyrot: Q1: quaternion is zero: ...".
    warnings warn0(err, "Q0"), warn1(err, "Q1");
    // t is a fraction of the way from Q0 to Q1: 25 is no percentage.
    const auto outside = std::find_if(o.ts.begin(), o.ts.end(), [](double h) { return h < 0 || h > 1; });
    if (outside != o.ts.end())
        print_error(err, fmt::format("warning: -t {} is outside [0, 1]: {} extrapolates beyond Q0 and Q1 (t is a "
                                     "fraction of the way, not a percentage)",
                                     *outside, to_string(how)));
    const track t{"", o.euler, {make_key(operand("Q0", o.q0, o, 0), settings_of(o), warn0),
                                make_key(operand("Q1", o.q1, o, 1), settings_of(o), warn1)},
                    std::nullopt};
    const rotation_curve curve(t, how, o.way);
    table_info info;
    info.times = time_columns::time_only;
    info.time_name = "t";
    info.method = to_string(how);
    // Rows are written as they are made: --steps may ask for millions.
    const std::optional<std::string> target = output_path(o);
    const format to = o.to.value_or(target ? format_of_path(*target).value_or(format::csv) : format::csv);
    check_output_format(o, to, target);
    const auto table = open_table(to, target, out, info, writing(o, t.euler), warn0);
    table->begin_track("", channels{}, track_interpolation{});
    const auto row = [&](double h) {
        const quat q = h == 0 ? curve.at_key(0) : h == 1 ? curve.at_key(1) : curve.at(0, h);
        table->row(table_row{{h, std::nullopt, q, std::nullopt}});
    };
    for (double h : o.ts) row(h);
    if (o.steps)
        for (int i = 0; i <= *o.steps; ++i) row(static_cast<double>(i) / *o.steps);
    table->finish();
    return 0;
}

}  // namespace keyrot::detail
