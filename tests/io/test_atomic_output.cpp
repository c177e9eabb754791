// Output transactions: a folder is exactly its old content or exactly the new one; the user's own
// files survive; stale outputs do not; one writer at a time; what a killed run left is cleaned up.
// (The kill itself, at every step of a real command's commit: tests/apps/crash_consistency.py.)
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/io/atomic_output.hpp"

namespace surfgrow::io {
namespace {

namespace fs = std::filesystem;

std::set<std::string> names_in(const fs::path& dir) {
    std::set<std::string> out;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
        out.insert(e.path().filename().string());
    return out;
}

void put(OutputTransaction& tx, const std::string& name, const std::string& text) {
    tx.add(name, [&](std::ostream& o) { o << text; });
}

// A pid no process has: a child that has exited and been reaped.
long dead_pid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return child;
}

ino_t inode_of(const fs::path& p) {
    struct stat st {};
    EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
    return st.st_ino;
}

TEST(OutputTransaction, ANewResultReplacesEveryEarlierOutputAndKeepsTheUsersFiles) {
    test::TempDir tmp;
    const fs::path out = tmp / "out";
    {
        OutputTransaction tx(out);
        put(tx, "surfaces.json", "old");
        put(tx, "planes.json", "old planes");
        tx.commit();
    }
    test::write_bytes(out / "notes.txt", "mine");
    fs::create_directory(out / "photos");
    test::write_bytes(out / "photos" / "a.jpg", "jpg");
    const ino_t notes = inode_of(out / "notes.txt");

    OutputTransaction tx(out, [](std::string_view n) { return n.ends_with(".json"); });
    put(tx, "surfaces.json", "new");
    tx.commit();
    EXPECT_EQ(names_in(out), (std::set<std::string>{"surfaces.json", "notes.txt", "photos"}));
    EXPECT_EQ(test::read_bytes(out / "surfaces.json"), "new");
    EXPECT_EQ(test::read_bytes(out / "notes.txt"), "mine");
    EXPECT_EQ(test::read_bytes(out / "photos" / "a.jpg"), "jpg");
    EXPECT_EQ(inode_of(out / "notes.txt"), notes) << "kept by a hard link, not copied";
    EXPECT_EQ(tx.removed(), std::vector<std::string>{"planes.json"});
    // Nothing beside the folder but its lock.
    EXPECT_EQ(names_in(tmp.path()), (std::set<std::string>{"out", ".out.lock"}));
}

TEST(OutputTransaction, AnAmendKeepsEverythingButWhatItWritesOrDrops) {
    test::TempDir tmp;
    const fs::path out = tmp / "out";
    {
        OutputTransaction tx(out);
        for (const char* n : {"surfaces.json", "planes.json", "coverage.json", "coverage.csv"})
            put(tx, n, "old");
        tx.commit();
    }
    OutputTransaction tx(out);
    put(tx, "planes.json", "new");
    tx.drop("coverage.json");
    tx.drop("coverage.csv");
    tx.drop("planes.json");  // staged wins over dropped
    tx.drop("never-there");
    tx.commit();
    EXPECT_EQ(names_in(out), (std::set<std::string>{"surfaces.json", "planes.json"}));
    EXPECT_EQ(test::read_bytes(out / "surfaces.json"), "old");
    EXPECT_EQ(test::read_bytes(out / "planes.json"), "new");
    EXPECT_EQ(tx.removed(), (std::vector<std::string>{"coverage.csv", "coverage.json"}));
}

TEST(OutputTransaction, AFailureBeforeCommitLeavesTheFolderAndNoStaging) {
    test::TempDir tmp;
    const fs::path out = tmp / "out";
    test::write_bytes(tmp / "placeholder", "");
    fs::create_directory(out);
    test::write_bytes(out / "surfaces.json", "good");
    try {
        OutputTransaction tx(out, [](std::string_view) { return true; });
        put(tx, "surfaces.json", "new");
        tx.add("labels.txt",
               [](std::ostream&) { throw Error(ErrorCode::kMalformedInput, "late failure"); });
        tx.commit();
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kMalformedInput);
    }
    EXPECT_EQ(names_in(out), std::set<std::string>{"surfaces.json"});
    EXPECT_EQ(test::read_bytes(out / "surfaces.json"), "good");
    EXPECT_EQ(names_in(tmp.path()), (std::set<std::string>{"out", ".out.lock", "placeholder"}));
}

TEST(OutputTransaction, ASecondWriterIsRefusedNamingTheFirst) {
    test::TempDir tmp;
    const fs::path out = tmp / "out";
    OutputTransaction first(out);
    try {
        OutputTransaction second(out);
        FAIL() << "two writers at once";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCannotWrite);
        const std::string what = e.what();
        EXPECT_NE(what.find("another surfgrow run"), std::string::npos) << what;
        EXPECT_NE(what.find(std::to_string(::getpid())), std::string::npos) << what;
        EXPECT_NE(what.find(out.string()), std::string::npos) << what;
    }
    put(first, "a.txt", "a");
    first.commit();
    // Released with the first transaction: the next one goes ahead.
    { OutputTransaction later(out); }
    EXPECT_EQ(test::read_bytes(out / "a.txt"), "a");
}

TEST(OutputTransaction, WhatAKilledRunLeftIsCleanedUpOrPutBack) {
    test::TempDir tmp;
    const fs::path out = tmp / "out";
    // Killed after staging: its staging folder is removed by the next run.
    fs::create_directories(tmp / ".out.staging-12345");
    test::write_bytes(tmp / ".out.staging-12345" / "surfaces.json", "half");
    // Killed between the fallback's two renames: the old folder is aside and out/ is missing.
    fs::create_directories(tmp / ".out.old-12345");
    test::write_bytes(tmp / ".out.old-12345" / "surfaces.json", "old");
    {
        OutputTransaction tx(out);
        EXPECT_EQ(test::read_bytes(out / "surfaces.json"), "old") << "the old result is back";
    }
    EXPECT_EQ(names_in(tmp.path()), (std::set<std::string>{"out", ".out.lock"}));

    // Temporaries of earlier versions' per-file commits, from a process that is gone, are not
    // carried into the new result; a living process's temporary is not touched.
    const std::string stale = ".planes.json.tmp-" + std::to_string(dead_pid()) + "-3";
    const std::string live = ".planes.json.tmp-" + std::to_string(::getpid()) + "-4";
    test::write_bytes(out / stale, "x");
    test::write_bytes(out / live, "y");
    OutputTransaction tx(out);
    put(tx, "planes.json", "new");
    tx.commit();
    EXPECT_EQ(names_in(out), (std::set<std::string>{"surfaces.json", "planes.json", live}));
}

TEST(OutputTransaction, ASymlinkedFolderKeepsPointingAtTheNewResult) {
    test::TempDir tmp;
    fs::create_directories(tmp / "data" / "run1");
    test::write_bytes(tmp / "data" / "run1" / "surfaces.json", "old");
    fs::create_directory_symlink(tmp / "data" / "run1", tmp / "latest");
    OutputTransaction tx(tmp / "latest/", [](std::string_view) { return true; });
    put(tx, "surfaces.json", "new");
    tx.commit();
    EXPECT_TRUE(fs::is_symlink(tmp / "latest"));
    EXPECT_EQ(test::read_bytes(tmp / "latest" / "surfaces.json"), "new");
    EXPECT_EQ(test::read_bytes(tmp / "data" / "run1" / "surfaces.json"), "new");
}

TEST(OutputTransaction, CreatesTheFolderAndRefusesAFile) {
    test::TempDir tmp;
    const fs::path out = tmp / "a" / "b" / "out";
    {
        OutputTransaction tx(out);
        put(tx, "x.txt", "x");
        EXPECT_FALSE(fs::exists(out)) << "nothing visible before commit";
        tx.commit();
    }
    EXPECT_EQ(test::read_bytes(out / "x.txt"), "x");
    test::write_bytes(tmp / "file", "f");
    try {
        OutputTransaction tx(tmp / "file");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCannotWrite);
        EXPECT_NE(std::string(e.what()).find("not a folder"), std::string::npos) << e.what();
    }
    EXPECT_EQ(test::read_bytes(tmp / "file"), "f");
}

TEST(WriteAtomically, ReplacesTheFileAndRemovesDeadRunsTemporaries) {
    test::TempDir tmp;
    const fs::path file = tmp / "render.png";
    test::write_bytes(file, "old");
    const std::string stale = ".render.png.tmp-" + std::to_string(dead_pid()) + "-0";
    const std::string other = ".other.png.tmp-" + std::to_string(dead_pid()) + "-0";
    test::write_bytes(tmp / stale, "half");
    test::write_bytes(tmp / other, "half");
    write_atomically(file, [](std::ostream& o) { o << "new"; });
    EXPECT_EQ(test::read_bytes(file), "new");
    EXPECT_EQ(names_in(tmp.path()), (std::set<std::string>{"render.png", other}));
    try {
        write_atomically(file, [](std::ostream&) { throw Error(ErrorCode::kInternal, "boom"); });
        FAIL();
    } catch (const Error&) {
    }
    EXPECT_EQ(test::read_bytes(file), "new");
    EXPECT_EQ(names_in(tmp.path()), (std::set<std::string>{"render.png", other}));
}

}  // namespace
}  // namespace surfgrow::io
