// SPDX-License-Identifier: MIT
#pragma once
// The commands, a file each (src/app/*_command.cpp), which run() calls.
#include <iosfwd>

namespace keyrot {
struct options;
}

namespace keyrot::detail {

int run_transform(const options& o, std::istream& in, std::ostream& out, std::ostream& err);  // resample, convert, reduce
int run_slerp(const options& o, std::ostream& out, std::ostream& err);
int run_compare(const options& o, std::istream& in, std::ostream& out, std::ostream& err);
int run_info(const options& o, std::istream& in, std::ostream& out, std::ostream& err);
int run_plot(const options& o, std::istream& in, std::ostream& out, std::ostream& err);

}  // namespace keyrot::detail
