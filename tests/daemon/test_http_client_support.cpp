// The pure parts of kewd's HTTP client (design §5.7): when the next request goes out
// (interval, backoff, Retry-After), what a server's answer asks for, and how credentials
// files are read.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "credentials.hpp"
#include "http_client.hpp"
#include "retry_schedule.hpp"

namespace kew::daemon {
namespace {

TEST(RetrySchedule, PollsAtTheIntervalWhileAnswered) {
  RetrySchedule s(1.0, 0.5, 30.0);
  EXPECT_EQ(s.after_success(), 1.0);
  EXPECT_EQ(s.after_success(), 1.0);
  EXPECT_EQ(s.consecutive_failures(), 0u);
}

TEST(RetrySchedule, BacksOffDoublingToTheMostThenStartsAgain) {
  RetrySchedule s(0.1, 0.5, 4.0);
  EXPECT_EQ(s.after_failure(), 0.5);
  EXPECT_EQ(s.after_failure(), 1.0);
  EXPECT_EQ(s.after_failure(), 2.0);
  EXPECT_EQ(s.after_failure(), 4.0);
  EXPECT_EQ(s.after_failure(), 4.0);
  EXPECT_EQ(s.consecutive_failures(), 5u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(s.after_failure(), 4.0);  // no overflow however long
  EXPECT_EQ(s.after_success(), 0.1);
  EXPECT_EQ(s.after_failure(), 0.5);
}

TEST(RetrySchedule, NeverSoonerThanTheIntervalOrWhatTheServerAsked) {
  RetrySchedule slow(10.0, 0.5, 4.0);
  EXPECT_EQ(slow.after_failure(), 10.0);
  RetrySchedule s(1.0, 0.5, 4.0);
  EXPECT_EQ(s.after_failure(60.0), 60.0) << "a server that names its limit knows it, beyond the most backoff";
  EXPECT_EQ(s.after_success(30.0), 30.0);
  EXPECT_EQ(s.after_success(0.2), 1.0);
}

HttpResponse answer_with(std::vector<std::pair<std::string, std::string>> headers) {
  HttpResponse r;
  r.outcome = HttpOutcome::Answered;
  r.headers = std::move(headers);
  return r;
}

TEST(HttpResponse, RetryAfterInSecondsAsADateAndOpenskysHeader) {
  EXPECT_EQ(answer_with({{"retry-after", "120"}}).retry_after_s(0), 120.0);
  // Sun, 06 Nov 1994 08:49:37 GMT is 784111777 (RFC 9110's example date).
  EXPECT_EQ(answer_with({{"retry-after", "Sun, 06 Nov 1994 08:49:37 GMT"}}).retry_after_s(784111777.0 - 42), 42.0);
  EXPECT_EQ(answer_with({{"retry-after", "Sun, 06 Nov 1994 08:49:37 GMT"}}).retry_after_s(784111777.0 + 5), 0.0);
  EXPECT_EQ(answer_with({{"x-rate-limit-retry-after-seconds", "3600"}, {"retry-after", "5"}}).retry_after_s(0), 3600.0);
  EXPECT_FALSE(answer_with({{"retry-after", "soon"}}).retry_after_s(0));
  EXPECT_FALSE(answer_with({{"retry-after", "-3"}}).retry_after_s(0));
  EXPECT_FALSE(answer_with({}).retry_after_s(0));
  EXPECT_EQ(answer_with({{"etag", "\"v1\""}}).header("etag"), "\"v1\"");
}

TEST(Credentials, OpenskysJsonIsOAuth2AndALineIsBasic) {
  const Credentials oauth = parse_credentials(R"({"clientId": "me-api-client", "clientSecret": "abc"})" "\n");
  EXPECT_TRUE(oauth.oauth2());
  EXPECT_EQ(oauth.client_id, "me-api-client");
  EXPECT_EQ(oauth.client_secret, "abc");
  const Credentials basic = parse_credentials("user:pa:ss\n");
  EXPECT_FALSE(basic.oauth2());
  EXPECT_EQ(basic.basic, "user:pa:ss");
}

TEST(Credentials, NeitherFormIsRefusedWithoutQuotingTheSecret) {
  for (const char* text : {"{\"clientId\": \"hunter2\"}", "{\"clientId\": 1, \"clientSecret\": \"hunter2\"}",
                           "{hunter2", "hunter2", ":hunter2", "user:hunter2\nsecond line"}) {
    try {
      parse_credentials(text);
      ADD_FAILURE() << "accepted " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).find("hunter2"), std::string::npos) << e.what();
    }
  }
}

TEST(SecretFile, TrimmedOneLineAndExposureWarned) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("kew-secret-" + std::to_string(::getpid()))).string();
  {
    std::ofstream f(path);
    f << "  key-123 \n";
  }
  ::chmod(path.c_str(), 0600);
  EXPECT_EQ(read_secret_file(path), "key-123");
  EXPECT_FALSE(secret_file_exposure(path));
  ::chmod(path.c_str(), 0644);
  ASSERT_TRUE(secret_file_exposure(path));
  EXPECT_NE(secret_file_exposure(path)->find("may be read by every user"), std::string::npos);
  {
    std::ofstream f(path);
    f << "\n \n";
  }
  EXPECT_THROW(read_secret_file(path), std::runtime_error);
  {
    std::ofstream f(path);
    f << "one\ntwo\n";
  }
  EXPECT_THROW(read_secret_file(path), std::runtime_error);
  std::remove(path.c_str());
  try {
    read_secret_file(path);
    ADD_FAILURE();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
  }
}

}  // namespace
}  // namespace kew::daemon
