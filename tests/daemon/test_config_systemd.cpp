// kewd --check-config before the service ever started (design §5.7): the directories the
// unit has systemd create (LogsDirectory=, StateDirectory=) may be missing then, and pass
// with a note while their parent exists; any other missing directory still fails, and
// kewd about to start trusts nothing.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "kew/daemon/config.hpp"

namespace kew::daemon {
namespace {

namespace fs = std::filesystem;

class SystemdDirectories : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("kew-systemd-" + std::to_string(::getpid()));
    fs::create_directories(root_ / "var" / "log");
    fs::create_directories(root_ / "var" / "lib");
    options_.created_by_systemd = {(root_ / "var/log/kew").string(), (root_ / "var/lib/kew").string()};
  }
  void TearDown() override { fs::remove_all(root_); }
  Config config(const std::string& alert_log, const std::string& state) const {
    return parse_config("[service]\nalert_log = \"" + (root_ / alert_log).string() + "\"\nstate_directory = \"" +
                        (root_ / state).string() + "\"\n");
  }

  fs::path root_;
  CheckOptions options_;
};

TEST_F(SystemdDirectories, ThePackagedLayoutPassesBeforeTheFirstStartWithNotes) {
  const Config packaged = config("var/log/kew/alerts.jsonl", "var/lib/kew");
  const std::vector<std::string> notes = check_config(packaged, options_);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("[service] alert_log"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("systemd creates it when kewd.service starts"), std::string::npos) << notes[0];
  EXPECT_NE(notes[1].find("[service] state_directory"), std::string::npos) << notes[1];
  // kewd about to start: what systemd should have made must be there.
  EXPECT_THROW(check_config(packaged, false), config::ConfigError);
}

TEST_F(SystemdDirectories, ImpossiblePathsStillFail) {
  // Below the directory systemd makes, or where its parent is missing or a file.
  EXPECT_THROW(check_config(config("var/log/kew/more/alerts.jsonl", "var/lib/kew"), options_), config::ConfigError);
  fs::remove_all(root_ / "var" / "lib");
  EXPECT_THROW(check_config(config("var/log/kew/alerts.jsonl", "var/lib/kew"), options_), config::ConfigError);
  std::ofstream(root_ / "var" / "lib") << "a file";
  EXPECT_THROW(check_config(config("var/log/kew/alerts.jsonl", "var/lib/kew"), options_), config::ConfigError);
  // A file where systemd's directory goes is no directory it can make.
  std::ofstream(root_ / "var" / "log" / "kew") << "a file";
  fs::remove(root_ / "var" / "lib");
  fs::create_directories(root_ / "var" / "lib");
  EXPECT_THROW(check_config(config("var/log/kew/alerts.jsonl", "var/lib/kew"), options_), config::ConfigError);
}

TEST_F(SystemdDirectories, ExistingDirectoriesAreCheckedAsAlways) {
  fs::create_directories(root_ / "var" / "log" / "kew");
  fs::create_directories(root_ / "var" / "lib" / "kew");
  EXPECT_TRUE(check_config(config("var/log/kew/alerts.jsonl", "var/lib/kew"), options_).empty());
}

TEST(SystemdDirectoriesOfTheUnit, AreTheLogsAndStateDirectoriesOfKewdService) {
  EXPECT_EQ(systemd_directories(), (std::vector<std::string>{"/var/log/kew", "/var/lib/kew"}));
}

}  // namespace
}  // namespace kew::daemon
