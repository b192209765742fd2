// Counts its steps until the run ends and writes them down.
#include <cstdlib>
#include <fstream>
#include <string>

#include <webots/Robot.hpp>

int main() {
  webots::Robot robot;
  const int time_step = static_cast<int>(robot.getBasicTimeStep());
  int steps = 0;
  while (robot.step(time_step) != -1)
    steps++;
  const char *dir = std::getenv("SWARM_LOG");
  std::ofstream out(std::string(dir ? dir : ".") + "/tally.json");
  out << "{\"steps\": " << steps << ", \"time\": " << robot.getTime() << "}\n";
  return 0;
}
