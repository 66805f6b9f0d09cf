// The keys of an http input (design §5.7): the URL, the poll's interval, timeout and
// backoff, the size limit, headers, and where secrets come from (files only); OpenSky's
// request limits enforced where the file names its API.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "expect_config_error.hpp"
#include "kew/daemon/config.hpp"

namespace kew::daemon {
namespace {

using config_test::expect_error;

const std::string kInput = "[[input]]\ntransport = \"http\"\nformat = \"aircraft-json\"\n";

TEST(HttpInputConfig, ReadsEveryKey) {
  const Config c = parse_config(kInput + R"(address = "https://adsb.example/api/v2/lat/29.9/lon/-95.3/dist/250"
poll_interval_s = 2.5
timeout_s = 4
reconnect_min_s = 0.5
reconnect_max_s = 20
max_response_bytes = 1048576
headers = ["Accept: application/json", "X-RapidAPI-Host: adsb.example"]
secret_header = "api-auth"
secret_file = "/etc/kew/adsb.key"
credentials_file = "/etc/kew/credentials.json"
token_url = "https://auth.example/token"
ca_file = "/etc/kew/ca.pem"
)",
                                "t.toml");
  ASSERT_EQ(c.inputs.size(), 1u);
  const InputConfig& in = c.inputs[0];
  EXPECT_EQ(in.transport, Transport::Http);
  EXPECT_EQ(in.address, "https://adsb.example/api/v2/lat/29.9/lon/-95.3/dist/250");
  EXPECT_EQ(in.poll_interval_s, 2.5);
  EXPECT_EQ(in.timeout_s, 4.0);
  EXPECT_EQ(in.reconnect_min_s, 0.5);
  EXPECT_EQ(in.reconnect_max_s, 20.0);
  EXPECT_EQ(in.max_response_bytes, 1048576u);
  EXPECT_EQ(in.headers, (std::vector<std::string>{"Accept: application/json", "X-RapidAPI-Host: adsb.example"}));
  EXPECT_EQ(in.secret_header, "api-auth");
  EXPECT_EQ(in.secret_file, "/etc/kew/adsb.key");
  EXPECT_EQ(in.credentials_file, "/etc/kew/credentials.json");
  EXPECT_EQ(in.token_url, "https://auth.example/token");
  EXPECT_EQ(in.ca_file, "/etc/kew/ca.pem");
}

TEST(HttpInputConfig, DefaultsSuitAReceiversAircraftJson) {
  const InputConfig in = parse_config(kInput + "address = \"http://127.0.0.1/tar1090/data/aircraft.json\"\n", "t.toml")
                             .inputs.at(0);
  EXPECT_EQ(in.poll_interval_s, 1.0);
  EXPECT_EQ(in.timeout_s, 10.0);
  EXPECT_EQ(in.max_response_bytes, 32u << 20);
  EXPECT_TRUE(in.secret_file.empty());
}

TEST(HttpInputConfig, AnAtSignAfterTheHostIsNoUser) {
  const Config c = parse_config(kInput + "address = \"https://adsb.example/api?by=ops@example.org#a@b\"\n", "t.toml");
  EXPECT_EQ(c.inputs[0].address, "https://adsb.example/api?by=ops@example.org#a@b");
}

TEST(HttpInputConfig, RefusesMistakesAtTheirLine) {
  expect_error(kInput + "address = \"127.0.0.1:8080\"\n", "t.toml:4: [input 1] address must be an http:// or https:// URL");
  expect_error(kInput + "address = \"ftp://h/a.json\"\n", "http:// or https:// URL");
  expect_error(kInput + "address = \"http:///a.json\"\n", "with a host");
  expect_error(kInput + "address = \"http://h/a b.json\"\n", "with a host");
  // Every log line that names the URL would show the password.
  expect_error(kInput + "address = \"https://user:secret@adsb.example/api\"\n", "user:password@host");
  expect_error(kInput + "address = \"http://token@adsb.example/api\"\n", "credentials_file");
  expect_error(kInput + "address = \"http://h/a.json\"\nheaders = [\"no colon\"]\n", "\"Name: value\" on one line");
  expect_error(kInput + "address = \"http://h/a.json\"\nheaders = [\"Bad Name: x\"]\n", "\"Name: value\"");
  expect_error(kInput + "address = \"http://h/a.json\"\nsecret_header = \"api-auth\"\n",
               "secret_header and secret_file come together");
  expect_error(kInput + "address = \"http://h/a.json\"\nsecret_file = \"/k\"\n", "come together");
  expect_error(kInput + "address = \"http://h/a.json\"\npoll_interval_s = 0.01\n", "poll_interval_s = 0.01 is outside");
  expect_error(kInput + "address = \"http://h/a.json\"\nmax_response_bytes = 10\n", "max_response_bytes = 10 is outside");
  expect_error(kInput + "address = \"http://h/a.json\"\npace = true\n", "pace is for transport file only");
  expect_error("[[input]]\ntransport = \"tcp-client\"\naddress = \"127.0.0.1:30003\"\nca_file = \"/x\"\n",
               "ca_file is for transport http only");
  expect_error("[[input]]\ntransport = \"udp\"\naddress = \"127.0.0.1:30003\"\nreconnect_min_s = 1\n",
               "reconnect_min_s is for transport tcp-client and http only");
}

TEST(HttpInputConfig, OpenskysRequestLimitsHold) {
  const std::string opensky = kInput + "address = \"https://opensky-network.org/api/states/all?lamin=45&lomin=5&lamax=48&lomax=11\"\n";
  expect_error(opensky, "OpenSky's API allows one request every 10 s without credentials");
  expect_error(opensky + "poll_interval_s = 9\n", "every 10 s without credentials");
  EXPECT_NO_THROW(parse_config(opensky + "poll_interval_s = 10\n", "t.toml"));
  expect_error(opensky + "poll_interval_s = 4\ncredentials_file = \"/etc/kew/credentials.json\"\n",
               "every 5 s with credentials");
  EXPECT_NO_THROW(parse_config(opensky + "poll_interval_s = 5\ncredentials_file = \"/etc/kew/c.json\"\n", "t.toml"));
}

}  // namespace
}  // namespace kew::daemon
