// SPDX-License-Identifier: MIT
#include "app/app.hpp"

#include "app/commands.hpp"

namespace keyrot {

namespace {

int run_command(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    switch (o.cmd) {
        case command::resample:
        case command::convert:
        case command::reduce: return detail::run_transform(o, in, out, err);
        case command::slerp: return detail::run_slerp(o, out, err);
        case command::compare: return detail::run_compare(o, in, out, err);
        case command::info: return detail::run_info(o, in, out, err);
        case command::plot: return detail::run_plot(o, in, out, err);
    }
    return 2;
}

}  // namespace

int run(const options& o, std::istream& in, std::ostream& out, std::ostream& err) {
    try {
        return run_command(o, in, out, err);
    } catch (const option_error& e) {
        if (!e.which) throw;
        throw in_flags(e);  // the core's, said in flags
    }
}

}  // namespace keyrot
