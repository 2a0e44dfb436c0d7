// A stand-in for the tev viewer at the protocol level: listens on 127.0.0.1 (a free port),
// takes one connection, and checks every packet the way tev reads them (length prefix, type,
// fields, exact data size), assembling the image from the updates.
#pragma once

#include <atomic>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "erpt/image_io.h"

namespace erpt::test {

class TevTestServer {
 public:
  TevTestServer();
  ~TevTestServer();
  int port() const { return port_; }
  // Waits (up to `seconds`) for the client to close the connection; false on time-out.
  bool waitForClose(double seconds);

  // What arrived (read after waitForClose).
  int creates = 0, updates = 0;
  std::string name;
  std::vector<std::string> channels;
  RgbImage image;                   // assembled from the updates
  std::vector<std::string> errors;  // protocol violations
  size_t largestPacket = 0;

 private:
  void serve();
  void handle(const std::string& packet);
  int listen_ = -1, port_ = 0;
  std::atomic<bool> closed_{false};
  std::thread thread_;
};

}  // namespace erpt::test
