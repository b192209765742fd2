// The C++ twin of tests/data/webots-swarm/controllers/shepherd/shepherd.py: a supervisor
// without wheels brings the stray e-puck home and orders the other to go.
#include <cstdio>
#include <cstdlib>
#include <string>

#include <webots/Emitter.hpp>
#include <webots/Field.hpp>
#include <webots/Node.hpp>
#include <webots/Supervisor.hpp>

using namespace webots;

static void vector(FILE *log, const char *name, const double *v) {
  std::fprintf(log, "\"%s\": [%.17g, %.17g, %.17g], ", name, v[0], v[1], v[2]);
}

int main() {
  Supervisor *supervisor = new Supervisor();
  int timeStep = static_cast<int>(supervisor->getBasicTimeStep());
  Emitter *emitter = supervisor->getEmitter("emitter");
  Field *stray = supervisor->getFromDef("STRAY")->getField("translation");
  Field *flock = supervisor->getFromDef("FLOCK")->getField("translation");
  double strayStart[3], flockStart[3];
  for (int i = 0; i < 3; i++) {
    strayStart[i] = stray->getSFVec3f()[i];
    flockStart[i] = flock->getSFVec3f()[i];
  }
  const double home[3] = {0.5, -0.5, 0.0};
  stray->setSFVec3f(home);
  int steps = 0;
  while (supervisor->step(timeStep) != -1) {
    steps++;
    std::string order = steps <= 20 ? "go" : "stop";
    emitter->send(order.c_str(), static_cast<int>(order.size()));
    if (steps == 40)
      break;
  }
  std::string path = std::string(std::getenv("SWARM_LOG")) + "/shepherd.json";
  FILE *log = std::fopen(path.c_str(), "w");
  std::fprintf(log, "{");
  vector(log, "stray", strayStart);
  vector(log, "flock_start", flockStart);
  vector(log, "flock_end", flock->getSFVec3f());
  std::fprintf(log, "\"channel\": %d, \"range\": %.17g}", emitter->getChannel(),
               emitter->getRange());
  std::fclose(log);
  delete supervisor;
  return 0;
}
