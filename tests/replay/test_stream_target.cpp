// kew-replay --to: the targets it streams records to (design §5.6, §5.9).
#include "kew/replay/stream_sender.hpp"

#include <gtest/gtest.h>

namespace kew::replay {
namespace {

using Protocol = StreamTarget::Protocol;

TEST(StreamTarget, TcpUdpAndNats) {
  const auto tcp = parse_stream_target("127.0.0.1:4748");
  ASSERT_TRUE(tcp);
  EXPECT_EQ(tcp->protocol, Protocol::Tcp);
  EXPECT_EQ(tcp->port, 4748);
  const auto udp = parse_stream_target("udp://[::1]:8600");
  ASSERT_TRUE(udp);
  EXPECT_EQ(udp->protocol, Protocol::Udp);
  EXPECT_EQ(udp->host, "::1");
  const auto nats = parse_stream_target("nats://127.0.0.1:4222/kew.feed.radar1");
  ASSERT_TRUE(nats);
  EXPECT_EQ(nats->protocol, Protocol::Nats);
  EXPECT_EQ(nats->host, "127.0.0.1");
  EXPECT_EQ(nats->port, 4222);
  EXPECT_EQ(nats->subject, "kew.feed.radar1");
}

TEST(StreamTarget, ANatsTargetNeedsASubjectToPublishTo) {
  std::string error;
  EXPECT_FALSE(parse_stream_target("nats://127.0.0.1:4222", &error));
  EXPECT_NE(error.find("needs a subject"), std::string::npos) << error;
  EXPECT_FALSE(parse_stream_target("nats://127.0.0.1:4222/", &error));
  EXPECT_FALSE(parse_stream_target("nats://127.0.0.1:4222/kew.>", &error));  // a wildcard is no destination
  EXPECT_FALSE(parse_stream_target("nats://127.0.0.1/kew.feed", &error));    // no port
}

TEST(StreamTarget, ANatsTargetNamesEveryServerOfACluster) {
  const auto one = parse_stream_target("nats://127.0.0.1:4222/kew.feed");
  ASSERT_TRUE(one);
  EXPECT_EQ(one->nats_servers, std::vector<std::string>{"nats://127.0.0.1:4222"});
  const auto three = parse_stream_target("nats://127.0.0.1:4222,nats://127.0.0.1:4223,[::1]:4224/kew.feed");
  ASSERT_TRUE(three);
  EXPECT_EQ(three->nats_servers,
            (std::vector<std::string>{"nats://127.0.0.1:4222", "nats://127.0.0.1:4223", "nats://[::1]:4224"}));
  EXPECT_EQ(three->host, "127.0.0.1");
  EXPECT_EQ(three->port, 4222);
  EXPECT_EQ(three->subject, "kew.feed");
  std::string error;
  EXPECT_FALSE(parse_stream_target("nats://127.0.0.1:4222,/kew.feed", &error));
  EXPECT_FALSE(parse_stream_target("nats://127.0.0.1:4222,127.0.0.1/kew.feed", &error));  // no port
  EXPECT_NE(error.find("127.0.0.1"), std::string::npos) << error;
}

}  // namespace
}  // namespace kew::replay
