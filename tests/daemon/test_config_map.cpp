// [http] tile_url and tile_attribution (design §5.8): the map's tile server, offline when
// unset; a URL template must be http(s) with {z}, {x} and {y}.
#include <gtest/gtest.h>

#include <string>

#include "expect_config_error.hpp"
#include "kew/daemon/config.hpp"

namespace kew::daemon {
namespace {

using config_test::expect_error;

TEST(MapConfig, OfflineByDefault) {
  const Config c = parse_config("[http]\nlisten = \"127.0.0.1:8747\"\n", "t.toml");
  EXPECT_EQ(c.http.tile_url, "");
  EXPECT_EQ(c.http.tile_attribution, "");
  EXPECT_EQ(default_config().http.tile_url, "");
}

TEST(MapConfig, ReadsATileServerAndItsAttribution) {
  const Config c = parse_config(R"([http]
tile_url = "https://tile.openstreetmap.org/{z}/{x}/{y}.png"
tile_attribution = "© OpenStreetMap contributors"
)",
                                "t.toml");
  EXPECT_EQ(c.http.tile_url, "https://tile.openstreetmap.org/{z}/{x}/{y}.png");
  EXPECT_EQ(c.http.tile_attribution, "© OpenStreetMap contributors");
  EXPECT_NO_THROW(parse_config("[http]\ntile_url = \"http://tiles.local:8080/{s}/{z}/{y}/{x}.webp?key=1\"\n", "t.toml"));
  EXPECT_NO_THROW(parse_config("[http]\ntile_url = \"\"\n", "t.toml"));
}

TEST(MapConfig, RefusesWhatIsNoTileTemplateAtItsLine) {
  expect_error("[http]\n\ntile_url = \"https://tiles.example/{z}/{x}.png\"\n",
               "t.toml:3: [http] tile_url = \"https://tiles.example/{z}/{x}.png\" must be an http:// or https:// URL "
               "template with {z}, {x} and {y}");
  expect_error("[http]\ntile_url = \"ftp://tiles.example/{z}/{x}/{y}.png\"\n", "must be an http:// or https://");
  expect_error("[http]\ntile_url = \"tiles.example/{z}/{x}/{y}.png\"\n", "must be an http:// or https://");
  expect_error("[http]\ntile_url = \"https://tiles.example/{z}/{x}/{y} .png\"\n", "no white space");
  expect_error("[http]\ntile_url = 3\n", "tile_url");
  expect_error("[http]\ntile_attribution = [\"a\"]\n", "tile_attribution");
}

}  // namespace
}  // namespace kew::daemon
