// Serial I/O for the logger: libserialport for real ports, POSIX termios for pseudo-terminals.

#include "pamkit/logger/serial_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <termios.h>
#include <unistd.h>

#include <libserialport.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "pamkit/error.hpp"

namespace pamkit::logger {

using pamkit::detail::message;

namespace {

std::string sp_error(enum sp_return code) {
  if (code == SP_ERR_FAIL) {
    char* text = sp_last_error_message();
    std::string out = text ? text : "unknown failure";
    sp_free_error_message(text);
    return out;
  }
  switch (code) {
    case SP_ERR_ARG:
      return "invalid argument (libserialport)";
    case SP_ERR_MEM:
      return "out of memory";
    case SP_ERR_SUPP:
      return "not supported by this port";
    default:
      return "libserialport error " + std::to_string(static_cast<int>(code));
  }
}

std::string resolve(const std::string& path) {
  char resolved[PATH_MAX];
  if (!::realpath(path.c_str(), resolved)) {
    throw Error(message("serial port ", path, ": ", std::strerror(errno)));
  }
  return resolved;
}

speed_t termios_speed(unsigned baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 500000:
      return B500000;
    case 1000000:
      return B1000000;
    case 2000000:
      return B2000000;
    default:
      return 0;
  }
}

}  // namespace

bool is_pseudo_terminal(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0 || !S_ISCHR(info.st_mode)) return false;
  // Unix98 pty slaves: major numbers 136-143 (Linux devices.txt).
  const unsigned major_number = major(info.st_rdev);
  return major_number >= 136 && major_number <= 143;
}

struct SerialPort::Native {
  struct sp_port* port = nullptr;
  ~Native() {
    if (port) {
      sp_close(port);
      sp_free_port(port);
    }
  }
};

SerialPort::SerialPort(const std::string& path, unsigned baud, bool assert_dtr) {
  device_ = resolve(path);
  pty_ = is_pseudo_terminal(device_);
  if (pty_) {
    fd_ = ::open(device_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) throw Error(message("serial port ", path, " (", device_, "): ", std::strerror(errno)));
    termios settings{};
    if (::tcgetattr(fd_, &settings) != 0) {
      const int error = errno;
      ::close(fd_);
      throw Error(message("serial port ", path, ": not a terminal: ", std::strerror(error)));
    }
    ::cfmakeraw(&settings);
    settings.c_cflag |= CLOCAL | CREAD;
    settings.c_cc[VMIN] = 1;
    settings.c_cc[VTIME] = 0;
    if (const speed_t speed = termios_speed(baud)) ::cfsetspeed(&settings, speed);
    ::tcsetattr(fd_, TCSANOW, &settings);  // no flush: a pty holds nothing stale
    return;
  }

  native_ = std::make_unique<Native>();
  enum sp_return result = sp_get_port_by_name(device_.c_str(), &native_->port);
  if (result != SP_OK) {
    throw Error(message("serial port ", path, " (", device_, "): ", sp_error(result)));
  }
  if ((result = sp_open(native_->port, SP_MODE_READ_WRITE)) != SP_OK) {
    throw Error(message("serial port ", path, " (", device_, "): cannot open: ", sp_error(result)));
  }
  const auto check = [&](enum sp_return r, const char* what) {
    if (r != SP_OK) throw Error(message("serial port ", path, ": cannot set ", what, ": ", sp_error(r)));
  };
  check(sp_set_baudrate(native_->port, static_cast<int>(baud)), "the baud rate");
  check(sp_set_bits(native_->port, 8), "8 data bits");
  check(sp_set_parity(native_->port, SP_PARITY_NONE), "no parity");
  check(sp_set_stopbits(native_->port, 1), "1 stop bit");
  check(sp_set_flowcontrol(native_->port, SP_FLOWCONTROL_NONE), "no flow control");
  check(sp_set_dtr(native_->port, assert_dtr ? SP_DTR_ON : SP_DTR_OFF), "DTR");
  check(sp_get_port_handle(native_->port, &fd_), "(get) the descriptor");
  // Bytes already buffered come from before the reset DTR just caused: drop them.
  if (assert_dtr) sp_flush(native_->port, SP_BUF_INPUT);
}

SerialPort::~SerialPort() {
  if (pty_ && fd_ >= 0) ::close(fd_);
}

SerialPort::Status SerialPort::read(std::uint8_t* buffer, std::size_t capacity, int timeout_ms, std::size_t& count) {
  count = 0;
  pollfd request{fd_, POLLIN, 0};
  const int ready = ::poll(&request, 1, timeout_ms);
  if (ready < 0) return errno == EINTR ? Status::kTimeout : Status::kDisconnected;
  if (ready == 0) return Status::kTimeout;
  if (request.revents & POLLIN) {
    const ssize_t n = ::read(fd_, buffer, capacity);
    if (n > 0) {
      count = static_cast<std::size_t>(n);
      return Status::kData;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return Status::kTimeout;
    return Status::kDisconnected;  // 0: end of file (hang-up); EIO: device gone
  }
  return (request.revents & (POLLHUP | POLLERR | POLLNVAL)) ? Status::kDisconnected : Status::kTimeout;
}

std::vector<PortInfo> list_ports() {
  struct sp_port** ports = nullptr;
  const enum sp_return result = sp_list_ports(&ports);
  if (result != SP_OK) throw Error(message("cannot list serial ports: ", sp_error(result)));
  std::vector<PortInfo> out;
  for (struct sp_port** p = ports; *p; ++p) {
    PortInfo info;
    info.path = sp_get_port_name(*p);
    if (const char* text = sp_get_port_description(*p)) info.description = text;
    if (sp_get_port_transport(*p) == SP_TRANSPORT_USB) sp_get_port_usb_vid_pid(*p, &info.usb_vid, &info.usb_pid);
    out.push_back(std::move(info));
  }
  sp_free_port_list(ports);
  std::error_code error;
  const std::filesystem::path by_id("/dev/serial/by-id");
  if (std::filesystem::is_directory(by_id, error)) {
    for (const auto& entry : std::filesystem::directory_iterator(by_id, error)) {
      const auto target = std::filesystem::canonical(entry.path(), error);
      if (error) continue;
      for (auto& info : out) {
        if (info.path == target.string()) info.by_id.push_back(entry.path().string());
      }
    }
  }
  return out;
}

}  // namespace pamkit::logger
