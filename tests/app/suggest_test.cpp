// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <optional>
#include <string>
#include <vector>

#include "suggest.hpp"

using keyrot::edit_distance;
using keyrot::likely_meant;

TEST_CASE("edit_distance counts a swap of neighbours as one edit, and ignores case") {
    CHECK(edit_distance("--fsp", "--fps") == 1);
    CHECK(edit_distance("slrep", "slerp") == 1);
    CHECK(edit_distance("QUAT", "quat") == 0);
    CHECK(edit_distance("", "abc") == 3);
    CHECK(edit_distance("kitten", "sitting") == 3);
}

TEST_CASE("likely_meant: a slip of the keyboard, the one nearest; else a name spelt out in full") {
    const std::vector<std::string> reps = {"axis-angle", "quat", "rotvec", "euler", "matrix", "matrix4"};
    CHECK(likely_meant("axisangle", reps, 9) == "axis-angle");
    CHECK(likely_meant("rotvc", reps, 5) == "rotvec");
    CHECK(likely_meant("Euler", reps, 5) == "euler");
    // Spelt out: the longest name of three characters or more it begins with.
    CHECK(likely_meant("quaternion", reps, 10) == "quat");
    CHECK(likely_meant("matrix3", reps, 7) == "matrix");  // one edit from two names: the one it spells out
    CHECK(likely_meant("euler_angles", reps, 12) == "euler");
    // Two edits for words past four letters, one up to four.
    CHECK(likely_meant("mtrx", reps, 4) == std::nullopt);
    CHECK(likely_meant("quta", reps, 4) == "quat");
    CHECK(likely_meant("linear", reps, 6) == std::nullopt);
    // As near two names as one another: no guess.
    CHECK(likely_meant("xyz", {"wxyz", "xyzw"}, 3) == std::nullopt);
    // Flags: dashes do not count as letters, and "-o" is spelt out by too much.
    const std::vector<std::string> flags = {"--fps", "--tol", "-o", "--output-dir"};
    CHECK(likely_meant("--fsp", flags, 3) == "--fps");
    CHECK(likely_meant("--tolerance", flags, 9) == "--tol");
    CHECK(likely_meant("-output", flags, 6) == std::nullopt);
    CHECK(likely_meant("anything", {}, 8) == std::nullopt);
}
