// Drains its receiver each step in a getQueueLength() loop and notes how many packets it
// read at each step and what they were.
#include <webots/Receiver.hpp>
#include <webots/Robot.hpp>

#include <cstdlib>
#include <fstream>
#include <string>

using namespace webots;

int main() {
  Robot *robot = new Robot();
  const int timeStep = static_cast<int>(robot->getBasicTimeStep());
  Receiver *rx = robot->getReceiver("receiver");
  rx->enable(timeStep);
  std::string counts, packets;
  int steps = 0;
  while (robot->step(timeStep) != -1 && steps < 25) {
    steps++;
    int read = 0;
    while (rx->getQueueLength() > 0) {
      const char *text = static_cast<const char *>(rx->getData());
      packets += std::string(packets.empty() ? "" : ", ") + "\"" + text + "\"";
      rx->nextPacket();
      read++;
    }
    counts += std::string(counts.empty() ? "" : ", ") + std::to_string(read);
  }
  const char *dir = std::getenv("SWARM_LOG");
  std::ofstream out(std::string(dir ? dir : ".") + "/drainer.json");
  out << "{\"counts\": [" << counts << "], \"packets\": [" << packets << "]}\n";
  delete robot;
  return 0;
}
