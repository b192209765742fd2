// A C++ controller: sends "ping N" on channel 4 at step N and notes the step at which each
// "pong N" comes back on channel 5; turns on the spot meanwhile.
#include <webots/Emitter.hpp>
#include <webots/Motor.hpp>
#include <webots/Receiver.hpp>
#include <webots/Robot.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

using namespace webots;

int main() {
  Robot *robot = new Robot();
  const int timeStep = static_cast<int>(robot->getBasicTimeStep());
  Emitter *tx = robot->getEmitter("tx");
  Receiver *rx = robot->getReceiver("rx");
  rx->enable(timeStep);
  Motor *left = robot->getMotor("left wheel motor");
  Motor *right = robot->getMotor("right wheel motor");
  left->setPosition(INFINITY);
  right->setPosition(INFINITY);
  left->setVelocity(-1.0);
  right->setVelocity(1.0);
  std::string back;
  int steps = 0;
  while (robot->step(timeStep) != -1 && steps < 20) {
    steps++;
    while (rx->getQueueLength() > 0) {
      const std::string text(static_cast<const char *>(rx->getData()), rx->getDataSize());
      back += (back.empty() ? "" : ", ") + ("[" + std::to_string(steps) + ", \"" + text + "\"]");
      rx->nextPacket();
    }
    const std::string ping = "ping " + std::to_string(steps);
    tx->send(ping.c_str(), static_cast<int>(ping.size()));
  }
  const char *dir = std::getenv("SWARM_LOG");
  std::ofstream out(std::string(dir ? dir : ".") + "/talker.json");
  out << "{\"back\": [" << back << "], \"steps\": " << steps << "}\n";
  delete robot;
  return 0;
}
