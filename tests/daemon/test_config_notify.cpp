// [[notify]] tables (design §5.10): every key, the defaults that differ between the json
// template and the templates people read, and the mistakes refused at their line.
#include <gtest/gtest.h>

#include <string>

#include "expect_config_error.hpp"
#include "kew/daemon/config.hpp"

namespace kew::daemon {
namespace {

using config_test::expect_error;

TEST(NotifyConfig, ReadsEveryKey) {
  const Config c = parse_config(R"([[notify]]
name = "ops-phone"
url = "https://ntfy.example/kew-alerts"
template = "ntfy"
token_file = "/etc/kew/ntfy.token"
headers = ["X-Site: EDDM"]
ca_file = "/etc/kew/ca.pem"
title = "kew EDDM"
min_severity = "warning"
states = ["new", "ended"]
kinds = ["apw"]
regions = ["EDDM-TMA"]
callsigns = ["DLH*", "N9?7LP"]
addresses = ["3c6444"]
volumes = ["EDR-1*", "watch-*"]
timeout_s = 4
backoff_min_s = 0.5
backoff_max_s = 120
max_per_minute = 6
coalesce_s = 12
outbox = 500
failing_after_s = 30
)",
                                "t.toml");
  ASSERT_EQ(c.notify.size(), 1u);
  const NotifyConfig& n = c.notify[0];
  EXPECT_EQ(n.name, "ops-phone");
  EXPECT_EQ(n.url, "https://ntfy.example/kew-alerts");
  EXPECT_EQ(n.format, NotifyTemplate::Ntfy);
  EXPECT_EQ(n.token_file, "/etc/kew/ntfy.token");
  EXPECT_EQ(n.headers, std::vector<std::string>{"X-Site: EDDM"});
  EXPECT_EQ(n.title, "kew EDDM");
  EXPECT_EQ(n.min_severity, Severity::Warning);
  EXPECT_EQ(n.states, (std::vector{NotifyState::New, NotifyState::Ended}));
  EXPECT_EQ(n.regions, std::vector<std::string>{"EDDM-TMA"});
  EXPECT_EQ(n.callsigns, (std::vector<std::string>{"DLH*", "N9?7LP"}));
  EXPECT_EQ(n.addresses, std::vector<std::string>{"3c6444"});
  EXPECT_EQ(n.kinds, std::vector<AlertKind>{AlertKind::Apw});
  EXPECT_EQ(n.volumes, (std::vector<std::string>{"EDR-1*", "watch-*"}));
  EXPECT_EQ(n.timeout_s, 4.0);
  EXPECT_EQ(n.backoff_min_s, 0.5);
  EXPECT_EQ(n.backoff_max_s, 120.0);
  EXPECT_EQ(n.max_per_minute, 6.0);
  EXPECT_EQ(n.coalesce_s, 12.0);
  EXPECT_EQ(n.outbox, 500u);
  EXPECT_EQ(n.failing_after_s, 30.0);
}

TEST(NotifyConfig, PeopleAreSparedWhatProgramsTakeWhole) {
  const Config c = parse_config(R"([[notify]]
name = "hook"
url = "http://127.0.0.1:9000/kew"
[[notify]]
name = "chat"
url_file = "/etc/kew/slack.url"
template = "slack"
)",
                                "t.toml");
  ASSERT_EQ(c.notify.size(), 2u);
  const NotifyConfig& hook = c.notify[0];
  EXPECT_EQ(hook.format, NotifyTemplate::Json);
  EXPECT_EQ(hook.min_severity, Severity::Caution);
  EXPECT_EQ(hook.states.size(), 4u);
  EXPECT_EQ(hook.max_per_minute, 0.0);
  EXPECT_EQ(hook.coalesce_s, 0.0);
  EXPECT_EQ(hook.kinds, (std::vector{AlertKind::Stca, AlertKind::Apw}));
  EXPECT_TRUE(hook.volumes.empty());
  const NotifyConfig& chat = c.notify[1];
  EXPECT_EQ(chat.url_file, "/etc/kew/slack.url");
  EXPECT_EQ(chat.states, (std::vector{NotifyState::New, NotifyState::Escalated, NotifyState::Ended}));
  EXPECT_EQ(chat.max_per_minute, 20.0);
  EXPECT_EQ(chat.coalesce_s, 30.0);
}

TEST(NotifyConfig, RefusesMistakesAtTheirLine) {
  const std::string head = "[[notify]]\nname = \"n\"\n";
  expect_error("[[notify]]\nurl = \"http://h/x\"\n", "a notifier needs a name");
  expect_error("[[notify]]\nname = \"a b\"\nurl = \"http://h/x\"\n", "letters, digits");
  expect_error(head, "url or url_file");
  expect_error(head + "url = \"http://h/x\"\nurl_file = \"/etc/u\"\n", "url or url_file");
  expect_error(head + "url = \"ftp://h/x\"\n", "http:// or https://");
  expect_error(head + "url = \"https://user:tk_secret@ntfy.example/kew\"\n", "user:password@host");
  expect_error(head + "url = \"http://h/x\"\ntemplate = \"pager\"\n", "expected one of json, ntfy");
  expect_error(head + "url_file = \"/u\"\ntemplate = \"discord\"\ntoken_file = \"/t\"\n", "takes no token");
  expect_error(head + "url = \"http://h/x\"\nmin_severity = \"none\"\n", "min_severity");
  expect_error(head + "url = \"http://h/x\"\nstates = [\"opened\"]\n", "one of new, escalated");
  expect_error(head + "url = \"http://h/x\"\nstates = []\n", "would never send");
  expect_error(head + "url = \"http://h/x\"\ncallsigns = [\"DLH 1\"]\n", "a word without blanks");
  expect_error(head + "url = \"http://h/x\"\nkinds = [\"tcas\"]\n", "one of stca, apw");
  expect_error(head + "url = \"http://h/x\"\nkinds = []\n", "no kind of alert");
  expect_error(head + "url = \"http://h/x\"\nvolumes = [\"\"]\n", "volumes: each entry");
  expect_error(head + "url = \"http://h/x\"\ncoalesce_s = 10\n", "json delivers every event");
  expect_error(head + "url = \"http://h/x\"\nbackoff_min_s = 10\nbackoff_max_s = 5\n", "below backoff_min_s");
  expect_error(head + "url = \"http://h/x\"\nretries = 3\n", "retries");
  expect_error(head + "url = \"http://h/x\"\n" + head + "url = \"http://h/y\"\n", "another notifier's");
}

TEST(NotifyConfig, CheckRefusesUnreadableSecrets) {
  Config c = parse_config("[[notify]]\nname = \"n\"\nurl = \"http://127.0.0.1/x\"\ntoken_file = \"/nonexistent/kew.token\"\n",
                          "t.toml");
  try {
    check_config(c, false);
    ADD_FAILURE() << "accepted a missing token file";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("[notify n] token_file"), std::string::npos) << e.what();
  }
}

TEST(NotifyConfig, ReplayNeverNotifies) {
  Config c = parse_config("[[notify]]\nname = \"n\"\nurl = \"http://127.0.0.1/x\"\n", "t.toml");
  ReplaySettings replay;
  replay.file = "/tmp/recording.ndjson";
  apply_replay(c, replay);
  EXPECT_TRUE(c.notify.empty());
}

}  // namespace
}  // namespace kew::daemon
