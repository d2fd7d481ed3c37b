// NMEA 0183 output for chart plotters (OpenCPN, and those fed through gpsd):
// RMC, GGA, VTG, HDT, ROT and RSA sentences with their checksums, formatted
// into caller buffers without allocation, and a non-blocking UDP sender (one
// datagram per sentence). Fixes are flagged either as plain autonomous GNSS
// fixes (the default: what gpsd and the plotters behind it display) or as
// simulated ones (which gpsd discards).
#pragma once

#include <netinet/in.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "bridge/geo.h"

namespace kelvin::bridge {

// How the sentences flag the fix.
enum class NmeaFixMode {
  // A GNSS satellite compass with an autonomous fix: RMC/VTG FAA mode A, GGA
  // quality 1 with `satellites` in use; heading and rate of turn with the
  // GNSS talker ($GPHDT, $GPROT). gpsd reports such fixes as 3D (mode 3);
  // its lexer drops the gyro talker HE.
  kAutonomous,
  // A simulator: FAA mode S, GGA quality 8 with no satellites, heading and
  // rate of turn from a gyro ($HEHDT, $HEROT). OpenCPN displays it; gpsd
  // (and so every plotter fed through it) reports no fix.
  kSimulated,
};
// "autonomous" or "simulated".
std::string_view NmeaFixModeName(NmeaFixMode mode);
// Parses a mode name; throws kelvin::ArgumentError naming `what` (e.g.
// "--nmea-fix"), the text and the valid names otherwise.
NmeaFixMode ParseNmeaFixMode(std::string_view text, std::string_view what);

// What the sentences report, in SI units.
struct NmeaFix {
  NmeaFixMode mode = NmeaFixMode::kAutonomous;
  double utc_seconds = 0;         // s since the UNIX epoch, time of the fix
  GeoPoint position;              // deg
  double speed_over_ground = 0;   // m/s
  double course_over_ground = 0;  // rad, clockwise from north
  double heading = 0;             // rad, true, clockwise from north
  double yaw_rate = 0;            // rad/s, positive turning to starboard
  double rudder_angle = 0;        // rad, positive to starboard
  int satellites = 12;            // in use, reported by GGA in autonomous mode (0 to 99)
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
std::size_t FormatRmc(const NmeaFix& fix, std::span<char> out);  // $GPRMC, mode A or S
std::size_t FormatGga(const NmeaFix& fix, std::span<char> out);  // $GPGGA, quality 1 or 8
std::size_t FormatVtg(const NmeaFix& fix, std::span<char> out);  // $GPVTG, mode A or S
std::size_t FormatHdt(const NmeaFix& fix, std::span<char> out);  // $GPHDT or $HEHDT
std::size_t FormatRot(const NmeaFix& fix, std::span<char> out);  // $GPROT or $HEROT, deg/min, negative to port
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
