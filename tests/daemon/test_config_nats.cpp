// The NATS servers and replicas of a kewd file (design §5.9): a cluster's servers as a
// list (`servers`) or one string (`url`, comma-separated), each URL checked so that a file
// that passes --check-config names servers the client can reach; `replicas` 1–5, copied
// to the feed streams of NATS inputs, which name their servers the same two ways.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "kew/config/nats_servers.hpp"
#include "expect_config_error.hpp"
#include "kew/daemon/config.hpp"

namespace kew::daemon {
namespace {

using Servers = std::vector<std::string>;
using config_test::expect_error;

TEST(NatsServers, OneUrlIsOneServer) {
  EXPECT_EQ(config::parse_nats_servers("nats://10.0.0.5:4222"), Servers{"nats://10.0.0.5:4222"});
  for (const char* url : {"nats://bus.example:4222", "tls://bus.example:4443", "nats://[::1]:4222", "nats://bus",
                          "nats://kew:secret@bus:4222", "nats://s3cr3t-token@[fd00::1]"})
    EXPECT_TRUE(config::valid_nats_server(url)) << url;
}

TEST(NatsServers, ACommaSeparatedUrlIsTheListOfItsServers) {
  EXPECT_EQ(config::parse_nats_servers("nats://h:4222,nats://h:4223, nats://h:4224"),
            (Servers{"nats://h:4222", "nats://h:4223", "nats://h:4224"}));
  EXPECT_EQ(config::join_nats_servers({"nats://h:4222", "nats://h:4223"}), "nats://h:4222,nats://h:4223");
}

TEST(NatsServers, AMalformedUrlIsRefusedWithItsReason) {
  const std::pair<const char*, const char*> refused[] = {
      {"", "names no NATS server"},
      {"nats://h:4222,", "between two commas or at an end"},
      {"nats://h:4222,,nats://h:4223", "between two commas"},
      {"h:4222", "no nats:// before the host"},
      {"http://h:4222", "the scheme is http, not nats or tls"},
      {"nats://h:0", "port 0"},
      {"nats://h:65536", "above 65535"},
      {"nats://h:42x", "not a decimal number"},
      {"nats://:4222", "empty host"},
      {"nats://::1:4222", "brackets"},
      {"nats://h:4222/kew", "no path"},
      {"nats://h:4222 nats://h:4223", "no path, space or comma"},
      {"nats://@h:4222", "nothing before '@'"},
  };
  for (const auto& [text, reason] : refused) {
    std::string error;
    EXPECT_FALSE(config::parse_nats_servers(text, &error)) << text;
    EXPECT_NE(error.find(reason), std::string::npos) << text << ": " << error;
  }
}

TEST(NatsConfig, ServersUrlAndReplicas) {
  const Config listed = parse_config(R"(
[nats]
servers = ["nats://10.0.0.5:4222", "nats://10.0.0.6:4222", "nats://10.0.0.7:4222"]
replicas = 3
)");
  EXPECT_EQ(listed.nats.servers, (Servers{"nats://10.0.0.5:4222", "nats://10.0.0.6:4222", "nats://10.0.0.7:4222"}));
  EXPECT_EQ(listed.nats.replicas, 3);
  // A comma-separated url names the same servers (the client is given them as a list).
  EXPECT_EQ(parse_config("[nats]\nurl = \"nats://10.0.0.5:4222,nats://10.0.0.6:4222,nats://10.0.0.7:4222\"\n")
                .nats.servers,
            listed.nats.servers);
  EXPECT_EQ(parse_config("[nats]\nurl = \"nats://10.0.0.5:4222\"\n").nats.servers, Servers{"nats://10.0.0.5:4222"});
  const Config none = parse_config("[nats]\nurl = \"\"\nservers = []\n");
  EXPECT_TRUE(none.nats.servers.empty());  // publish nothing, as the shipped file says
  EXPECT_EQ(none.nats.replicas, 1);
}

TEST(NatsConfig, ServersThatCannotConnectAreRefusedAtTheirLine) {
  expect_error("[nats]\nurl = \"nats://127.0.0.1:4222,\"\n", "t.toml:2: [nats] url = \"nats://127.0.0.1:4222,\"");
  expect_error("[nats]\nurl = \"127.0.0.1:4222\"\n", "t.toml:2: [nats] url = \"127.0.0.1:4222\" is not a NATS server");
  expect_error("[nats]\nservers = [\n  \"nats://a:4222\",\n  \"nats://b:99999\",\n]\n",
                 "t.toml:4: [nats] servers: \"nats://b:99999\" is not a NATS server");
  expect_error("[nats]\nservers = [\"nats://a:4222\", 4222]\n", "each entry is a NATS server URL");
  expect_error("[nats]\nservers = \"nats://a:4222\"\nurl = \"nats://b:4222\"\n", "give servers or url, not both");
  expect_error("[nats]\nurl = \"nats://a:4222\"\nreplicas = 0\n", "t.toml:3: [nats] replicas = 0 is outside [1, 5]");
  expect_error("[nats]\nurl = \"nats://a:4222\"\nreplicas = 6\n", "replicas = 6 is outside [1, 5]");
  expect_error("[nats]\nservers = []\nhot_standby = true\n", "hot_standby needs url or servers");
}

TEST(NatsConfig, NatsInputsNameTheirServersAsTheNatsTableDoes) {
  const Config c = parse_config(R"(
[nats]
servers = ["nats://10.0.0.5:4222", "nats://10.0.0.6:4222"]
replicas = 2
[[input]]
transport = "nats"
address = "feeds.radar"
durable = "kewd_a"
stream = "FEEDS"
[[input]]
transport = "nats"
address = "feeds.adsb"
nats_servers = ["nats://127.0.0.1:4223", "nats://127.0.0.1:4224"]
[[input]]
transport = "nats"
address = "feeds.mlat"
nats_url = "nats://127.0.0.1:4225,nats://127.0.0.1:4226"
)");
  ASSERT_EQ(c.inputs.size(), 3u);
  EXPECT_EQ(c.inputs[0].nats_servers, c.nats.servers);  // [nats]'s when the input names none
  EXPECT_EQ(c.inputs[0].stream_replicas, 2);            // the feed stream kewd creates
  EXPECT_EQ(c.inputs[1].nats_servers, (Servers{"nats://127.0.0.1:4223", "nats://127.0.0.1:4224"}));
  EXPECT_EQ(c.inputs[2].nats_servers, (Servers{"nats://127.0.0.1:4225", "nats://127.0.0.1:4226"}));
  expect_error("[[input]]\ntransport = \"nats\"\naddress = \"a\"\nnats_url = \"nats://a:4222,b:4222\"\n",
                 "t.toml:4: [input 1] nats_url = \"nats://a:4222,b:4222\"");
  expect_error("[[input]]\ntransport = \"udp\"\naddress = \"127.0.0.1:8600\"\nnats_servers = [\"nats://a:4222\"]\n",
                 "nats_servers is for transport nats only");
}

}  // namespace
}  // namespace kew::daemon
