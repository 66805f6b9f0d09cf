#include "tshark.hpp"

#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace kew::tshark {

namespace {

void put_le32(std::vector<std::byte>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::byte>((v >> (8 * i)) & 0xFF));
}
void put_le16(std::vector<std::byte>& out, std::uint16_t v) {
  out.push_back(static_cast<std::byte>(v & 0xFF));
  out.push_back(static_cast<std::byte>(v >> 8));
}
void put_be16(std::vector<std::byte>& out, std::size_t v) {
  out.push_back(static_cast<std::byte>((v >> 8) & 0xFF));
  out.push_back(static_cast<std::byte>(v & 0xFF));
}

constexpr std::uint16_t kAsterixPort = 8600;

/// One Ethernet frame carrying `payload` in a UDP datagram 127.0.0.1:8600 → :8600.
std::vector<std::byte> udp_frame(const Datagram& payload) {
  std::vector<std::byte> frame(12, std::byte{0});  // destination and source MAC
  put_be16(frame, 0x0800);                         // IPv4
  const std::size_t ip_start = frame.size();
  const std::size_t udp_length = 8 + payload.size();
  const std::array<unsigned, 12> ip_header{0x45, 0x00, 0, 0, 0x00, 0x00,
                                           0x40, 0x00, 64, 17, 0, 0};  // TTL 64, UDP
  for (unsigned v : ip_header) frame.push_back(static_cast<std::byte>(v));
  for (int i = 0; i < 2; ++i) {
    for (unsigned v : {127u, 0u, 0u, 1u}) frame.push_back(static_cast<std::byte>(v));
  }
  const std::size_t total = 20 + udp_length;
  frame[ip_start + 2] = static_cast<std::byte>(total >> 8);
  frame[ip_start + 3] = static_cast<std::byte>(total & 0xFF);
  std::uint32_t sum = 0;  // RFC 791 header checksum
  for (std::size_t i = 0; i < 20; i += 2) {
    sum += static_cast<std::uint32_t>(frame[ip_start + i]) << 8 |
           static_cast<std::uint32_t>(frame[ip_start + i + 1]);
  }
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  const std::uint32_t checksum = ~sum & 0xFFFF;
  frame[ip_start + 10] = static_cast<std::byte>(checksum >> 8);
  frame[ip_start + 11] = static_cast<std::byte>(checksum & 0xFF);
  put_be16(frame, kAsterixPort);
  put_be16(frame, kAsterixPort);
  put_be16(frame, udp_length);
  put_be16(frame, 0);  // no UDP checksum (allowed over IPv4)
  frame.insert(frame.end(), payload.begin(), payload.end());
  return frame;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::stringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

}  // namespace

std::vector<std::byte> make_pcap(const std::vector<Datagram>& datagrams) {
  std::vector<std::byte> out;
  put_le32(out, 0xA1B2C3D4);  // magic, microsecond resolution
  put_le16(out, 2);
  put_le16(out, 4);
  put_le32(out, 0);       // time zone
  put_le32(out, 0);       // accuracy
  put_le32(out, 65535);   // snap length
  put_le32(out, 1);       // Ethernet
  std::uint32_t second = 1714400000;
  for (const Datagram& d : datagrams) {
    const auto frame = udp_frame(d);
    put_le32(out, second++);
    put_le32(out, 0);
    put_le32(out, static_cast<std::uint32_t>(frame.size()));
    put_le32(out, static_cast<std::uint32_t>(frame.size()));
    out.insert(out.end(), frame.begin(), frame.end());
  }
  return out;
}

std::string write_pcap(const std::vector<Datagram>& datagrams, const std::string& path) {
  const auto bytes = make_pcap(datagrams);
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path;
}

bool on_path() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (!dir.empty() && ::access((dir + "/tshark").c_str(), X_OK) == 0) return true;
  }
  return false;
}

std::string run(const std::string& command) {
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return output;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) output.append(buffer.data(), n);
  ::pclose(pipe);
  return output;
}

std::vector<FieldValues> fields(const std::string& pcap, const std::vector<std::string>& fields) {
  std::string command = "tshark -n -r '" + pcap + "' -T fields -E separator=/t -E occurrence=a -E aggregator=';'";
  for (const auto& f : fields) command += " -e " + f;
  command += " 2>/dev/null";
  std::vector<FieldValues> frames;
  for (const std::string& line : split(run(command), '\n')) {
    if (line.empty()) continue;
    const auto columns = split(line, '\t');
    FieldValues values;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      values[fields[i]] = i < columns.size() && !columns[i].empty() ? split(columns[i], ';')
                                                                     : std::vector<std::string>{};
    }
    frames.push_back(std::move(values));
  }
  return frames;
}

std::string problems(const std::string& pcap) {
  return run("tshark -n -r '" + pcap +
             "' -Y '_ws.malformed || _ws.expert' -T fields -e frame.number -e _ws.expert.message"
             " 2>/dev/null");
}

}  // namespace kew::tshark
