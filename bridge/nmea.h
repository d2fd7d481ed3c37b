// NMEA 0183 output for chart plotters (OpenCPN and others): RMC, GGA (fix
// quality 8, simulation), VTG, HDT, ROT and RSA sentences with their
// checksums, formatted into caller buffers without allocation, and a
// non-blocking UDP sender (one datagram per sentence).
#pragma once

#include <netinet/in.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "bridge/geo.h"

namespace kelvin::bridge {

// What the sentences report, in SI units.
struct NmeaFix {
  double utc_seconds = 0;         // s since the UNIX epoch, time of the fix
  GeoPoint position;              // deg
  double speed_over_ground = 0;   // m/s
  double course_over_ground = 0;  // rad, clockwise from north
  double heading = 0;             // rad, true, clockwise from north
  double yaw_rate = 0;            // rad/s, positive turning to starboard
  double rudder_angle = 0;        // rad, positive to starboard
};

constexpr double kMetresPerSecondPerKnot = 1852.0 / 3600.0;
// The longest sentence NMEA 0183 allows, "$" to "\n" included.
constexpr std::size_t kNmeaMaxSentence = 82;

// XOR of the characters between '$' and '*' (the body without either).
std::uint8_t NmeaChecksum(std::string_view body);

// Each formatter writes one sentence "$...*hh\r\n" into `out` (NUL
// terminated) and returns its length without the NUL, or 0 if `out` is too
// small or a value is not finite. Precision: time 0.01 s, latitude and
// longitude 1e-5 minute, speeds 0.01 kn and 0.01 km/h, angles 0.01 deg, rate
// of turn 0.01 deg/min, rudder 0.1 deg.
std::size_t FormatRmc(const NmeaFix& fix, std::span<char> out);  // $GPRMC, mode S (simulator)
std::size_t FormatGga(const NmeaFix& fix, std::span<char> out);  // $GPGGA, quality 8
std::size_t FormatVtg(const NmeaFix& fix, std::span<char> out);  // $GPVTG, mode S
std::size_t FormatHdt(const NmeaFix& fix, std::span<char> out);  // $HEHDT
std::size_t FormatRot(const NmeaFix& fix, std::span<char> out);  // $HEROT, deg/min, negative to port
std::size_t FormatRsa(const NmeaFix& fix, std::span<char> out);  // $IIRSA, starboard (single) rudder

struct UdpEndpoint {
  std::string host = "127.0.0.1";
  int port = 10110;
  // Parses "host:port" with a numeric IPv4 host; throws kelvin::ArgumentError
  // naming `what` (e.g. "--nmea") and the text otherwise.
  static UdpEndpoint Parse(std::string_view text, std::string_view what);
  std::string ToString() const;
};

// Sends the six sentences of a fix as UDP datagrams. Never blocks: a full
// socket buffer or an unreachable port drops the datagram and counts it.
class NmeaUdpSender {
 public:
  // Throws kelvin::ArgumentError if the socket cannot be created.
  explicit NmeaUdpSender(const UdpEndpoint& endpoint);
  ~NmeaUdpSender();
  NmeaUdpSender(const NmeaUdpSender&) = delete;
  NmeaUdpSender& operator=(const NmeaUdpSender&) = delete;

  // Formats and sends RMC, GGA, VTG, HDT, ROT, RSA. No allocation.
  void Send(const NmeaFix& fix);

  long sentences_sent() const { return sent_; }
  long sentences_dropped() const { return dropped_; }

 private:
  void SendOne(std::size_t length);
  int fd_ = -1;
  sockaddr_in address_{};
  char buffer_[128] = {};
  long sent_ = 0;
  long dropped_ = 0;
};

}  // namespace kelvin::bridge
