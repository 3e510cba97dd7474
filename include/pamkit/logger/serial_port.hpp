#pragma once
/// \file
/// The serial line to the logger. Real ports (USB: /dev/ttyACM*, /dev/serial/by-id/...) are opened
/// and configured through libserialport (enumeration, 8N1 at the baud rate, DTR); pseudo-terminals,
/// which libserialport 0.1.1 refuses and which tests and socat bridges use, through plain POSIX
/// calls. Either way reading is a poll() on the descriptor, so a pulled cable shows the same way.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pamkit::logger {

/// A serial port the system knows.
struct PortInfo {
  std::string path;                ///< device, e.g. /dev/ttyACM0
  std::string description;         ///< what libserialport says about it (USB product name...)
  int usb_vid = -1;                ///< USB vendor id, -1 if not USB (0x2341, 0x2A03: Arduino)
  int usb_pid = -1;                ///< USB product id, -1 if not USB
  std::vector<std::string> by_id;  ///< /dev/serial/by-id names that point at it: they survive re-plugging
};

/// Every serial port libserialport enumerates, with its stable by-id names.
/// \throws Error if libserialport cannot list the ports.
std::vector<PortInfo> list_ports();

/// An open serial line. Not copyable; closes on destruction.
class SerialPort {
 public:
  /// Opens `path` (a symlink such as a by-id name is followed at each open) at `baud` 8N1, no
  /// flow control, raw. With `assert_dtr` DTR is raised, which resets an Arduino Mega.
  /// \throws Error naming the path and the reason if it cannot be opened or configured.
  SerialPort(const std::string& path, unsigned baud, bool assert_dtr);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  /// Outcome of a read.
  enum class Status { kData, kTimeout, kDisconnected };

  /// Waits up to `timeout_ms` for bytes and reads at most `capacity` of them into `buffer`.
  /// \param[out] count bytes read
  /// \return kDisconnected when the device went away (hang-up, EIO, end of file).
  Status read(std::uint8_t* buffer, std::size_t capacity, int timeout_ms, std::size_t& count);

  /// True when the path is a pseudo-terminal (opened without libserialport).
  bool is_pty() const { return pty_; }
  /// The device the path resolved to when it was opened (e.g. /dev/ttyACM0, /dev/pts/3).
  const std::string& device() const { return device_; }

 private:
  struct Native;
  std::unique_ptr<Native> native_;
  int fd_ = -1;
  bool pty_ = false;
  std::string device_;
};

/// True if `path` (after following symlinks) is a pseudo-terminal slave (/dev/pts/N).
bool is_pseudo_terminal(const std::string& path);

}  // namespace pamkit::logger
