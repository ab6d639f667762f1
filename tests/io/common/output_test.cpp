// SPDX-License-Identifier: MIT
// Atomic output: a file is replaced whole on commit, or not at all.
#include "io/common/output.hpp"

#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "helpers.hpp"
#include "keyrot/error.hpp"

using namespace keyrot;

namespace {

std::size_t files_in(const std::filesystem::path& dir) {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

/// The entries of `dir`, as far as they can be read: a process's entries
/// in /proc go when it ends, which other tests' processes do all the time.
std::vector<std::filesystem::path> entries(const std::filesystem::path& dir) {
    std::vector<std::filesystem::path> found;
    std::error_code ec;
    for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        found.push_back(it->path());
    return found;
}

/// The directories of /proc that are processes'.
std::vector<std::filesystem::path> processes() {
    std::vector<std::filesystem::path> found;
    for (const auto& entry : entries("/proc")) {
        const std::string name = entry.filename().string();
        if (name.find_first_not_of("0123456789") == std::string::npos) found.push_back(entry);
    }
    return found;
}

/// How many processes hold a file whose name began with `prefix` and was removed since.
std::size_t holders_of_removed(const std::string& prefix) {
    std::size_t found = 0;
    for (const auto& process : processes()) {
        for (const auto& fd : entries(process / "fd")) {
            std::error_code ec;
            const std::string target = std::filesystem::read_symlink(fd, ec).string();
            if (target.starts_with(prefix) && target.ends_with(" (deleted)")) {
                ++found;
                break;
            }
        }
    }
    return found;
}

/// How many of this process's children have ended and not been reaped.
std::size_t zombie_children() {
    std::size_t zombies = 0;
    for (const auto& process : processes()) {
        std::ifstream in(process / "stat");
        std::string stat((std::istreambuf_iterator<char>(in)), {});
        // pid (comm) state ppid ...: after the last ')', as comm may hold anything
        std::istringstream fields(stat.substr(stat.rfind(')') + 1));
        char state = 0;
        long ppid = 0;
        if (fields >> state >> ppid && state == 'Z' && ppid == ::getpid()) ++zombies;
    }
    return zombies;
}

}  // namespace

// (That a holder closes every other descriptor at once cannot be seen
// without a race: before it runs, it holds copies of them all.)
TEST_CASE("large replaced files are freed by processes of their own, which end") {
    const keyrot::test::scratch s;
    const auto path = s.dir / "out.csv";
    constexpr std::size_t replaced = 8;
    for (std::size_t i = 0; i < replaced; ++i) {
        {
            // past the size worth a process, and on disk: its blocks to be freed
            std::ofstream(path) << std::string(5 << 20, 'x');
            const int fd = ::open(path.c_str(), O_RDONLY);
            REQUIRE(::fsync(fd) == 0);
            ::close(fd);
        }
        write_file_atomically(path.string(), "new\n");
        CHECK(s.read(path) == "new\n");
        CHECK(files_in(s.dir) == 1);
    }
    // Each holder ends once it holds the last reference: nothing holds an old file for long.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (holders_of_removed((s.dir / ".out.csv.keyrot-").string()) > 0 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    CHECK(holders_of_removed((s.dir / ".out.csv.keyrot-").string()) == 0);
    // Ended holders are reaped as their places are used again: they do not
    // pile up in a process that replaces many files.
    CHECK(zombie_children() < replaced);
}

TEST_CASE("output_file: the old file until commit, the new one after, no temporary left") {
    const keyrot::test::scratch s;
    const auto& dir = s.dir;
    const auto path = dir / "out.csv";
    std::ofstream(path) << "old\n";
    ::chmod(path.c_str(), 0640);

    SUBCASE("committed") {
        output_file f(path.string());
        f.write("new ");
        f.write("text\n");
        CHECK(s.read(path) == "old\n");
        CHECK(files_in(dir) == 2);  // the temporary beside it
        f.commit();
        CHECK(s.read(path) == "new text\n");
        CHECK(files_in(dir) == 1);
        struct stat st {};
        REQUIRE(::stat(path.c_str(), &st) == 0);
        CHECK((st.st_mode & 07777) == 0640);  // the permissions of the file it replaced
    }
    SUBCASE("another name of the old file keeps the old text: the name is given the new file, not written over") {
        std::filesystem::create_hard_link(path, dir / "backup.csv");
        write_file_atomically(path.string(), "new\n");
        CHECK(s.read(path) == "new\n");
        CHECK(s.read(dir / "backup.csv") == "old\n");
        CHECK(files_in(dir) == 2);
    }
    SUBCASE("--output-dir's names: a link there is replaced, not written through; a directory is left as it is") {
        std::filesystem::create_symlink("out.csv", dir / "link.csv");
        write_file_atomically((dir / "link.csv").string(), "new\n", {.follow_links = false});
        CHECK_FALSE(std::filesystem::is_symlink(dir / "link.csv"));
        CHECK(s.read(dir / "link.csv") == "new\n");
        CHECK(s.read(path) == "old\n");
        std::filesystem::create_directory(dir / "table.csv");
        std::ofstream(dir / "table.csv" / "inside") << "kept\n";
        CHECK_THROWS_AS(write_file_atomically((dir / "table.csv").string(), "new\n", {.follow_links = false}), error);
        CHECK(s.read(dir / "table.csv" / "inside") == "kept\n");
        CHECK(files_in(dir) == 3);  // out.csv, link.csv, table.csv: no temporary, nothing moved aside
    }
    SUBCASE("dropped") {
        {
            output_file f(path.string());
            f.write("half a table");
        }
        CHECK(s.read(path) == "old\n");
        CHECK(files_in(dir) == 1);
    }
    SUBCASE("a new file, whole") {
        write_file_atomically((dir / "fresh.json").string(), "{}\n");
        CHECK(s.read(dir / "fresh.json") == "{}\n");
        CHECK(files_in(dir) == 2);
    }
    SUBCASE("a directory that does not exist: one line, nothing written") {
        try {
            write_file_atomically((dir / "missing" / "x.csv").string(), "x");
            FAIL("no error");
        } catch (const error& e) {
            CHECK(std::string(e.what()).find("missing/x.csv") != std::string::npos);
        }
    }
}

TEST_CASE("devices and descriptors are written straight into, files replaced") {
    CHECK_FALSE(replaced_on_commit("/dev/null"));
    CHECK_FALSE(replaced_on_commit("/dev/stdout"));
    const keyrot::test::scratch s;
    CHECK(replaced_on_commit((s.dir / "no_such_file.csv").string()));
}

TEST_CASE("write_to_stream says why a stream cannot be written") {
    std::ostringstream good;
    write_to_stream(good, "abc");
    CHECK(good.str() == "abc");
    std::ostringstream bad;
    bad.setstate(std::ios::badbit);
    CHECK_THROWS_AS(write_to_stream(bad, "abc"), error);
}

TEST_CASE("durable_batch: its files are put in place together at finish, or not at all") {
    const keyrot::test::scratch s;
    const auto& dir = s.dir;
    std::ofstream(dir / "f0.csv") << "old\n";
    // More files than a block of the signal handler's slots holds.
    constexpr int files = 150;
    SUBCASE("finished") {
        durable_batch batch;
        for (int i = 0; i < files; ++i)
            write_file_atomically((dir / ("f" + std::to_string(i) + ".csv")).string(), std::to_string(i) + "\n",
                                  {true, &batch});
        CHECK(s.read(dir / "f0.csv") == "old\n");  // written, closed, not yet in place
        CHECK(files_in(dir) == files + 1);
        batch.finish();
        CHECK(files_in(dir) == files);
        CHECK(s.read(dir / "f0.csv") == "0\n");
        CHECK(s.read(dir / "f149.csv") == "149\n");
    }
    SUBCASE("never finished (a usage error stopped the run)") {
        {
            durable_batch batch;
            for (int i = 0; i < files; ++i)
                write_file_atomically((dir / ("f" + std::to_string(i) + ".csv")).string(), "new\n", {true, &batch});
        }
        CHECK(files_in(dir) == 1);
        CHECK(s.read(dir / "f0.csv") == "old\n");
    }
    SUBCASE("without --fsync a batch is not used: each file is in place at once") {
        durable_batch batch;
        write_file_atomically((dir / "f0.csv").string(), "new\n", {false, &batch});
        CHECK(s.read(dir / "f0.csv") == "new\n");
    }
}
