// Webots' C++ Supervisor class (<webots/Supervisor.hpp>), as the reference manual's Supervisor
// page describes it (https://cyberbotics.com/doc/reference/supervisor): a Robot with mazesim's
// C supervisor functions.
#ifndef WB_SUPERVISOR_HPP
#define WB_SUPERVISOR_HPP

#include <string>

#include <webots/Node.hpp>
#include <webots/Robot.hpp>
#include <webots/supervisor.h>

namespace webots {
  class Supervisor : public Robot {
  public:
    enum SimulationMode {
      SIMULATION_MODE_PAUSE = WB_SUPERVISOR_SIMULATION_MODE_PAUSE,
      SIMULATION_MODE_REAL_TIME = WB_SUPERVISOR_SIMULATION_MODE_REAL_TIME,
      SIMULATION_MODE_FAST = WB_SUPERVISOR_SIMULATION_MODE_FAST
    };
    Supervisor() {}
    virtual ~Supervisor() {}
    Node *getRoot() { return Node::findNode(wb_supervisor_node_get_root()); }
    Node *getSelf() { return Node::findNode(wb_supervisor_node_get_self()); }
    Node *getFromDef(const std::string &name) {
      return Node::findNode(wb_supervisor_node_get_from_def(name.c_str()));
    }
    Node *getFromId(int id) { return Node::findNode(wb_supervisor_node_get_from_id(id)); }
    Node *getFromDevice(const Device *device) {
      return Node::findNode(wb_supervisor_node_get_from_device(device ? device->getTag() : 0));
    }
    Node *getSelected() { return Node::findNode(wb_supervisor_node_get_selected()); }
    bool virtualRealityHeadsetIsUsed() const {
      return wb_supervisor_virtual_reality_headset_is_used();
    }
    void simulationQuit(int status) { wb_supervisor_simulation_quit(status); }
    void simulationReset() { wb_supervisor_simulation_reset(); }
    void simulationResetPhysics() { wb_supervisor_simulation_reset_physics(); }
    SimulationMode simulationGetMode() const {
      return static_cast<SimulationMode>(wb_supervisor_simulation_get_mode());
    }
    void simulationSetMode(SimulationMode mode) {
      wb_supervisor_simulation_set_mode(static_cast<WbSimulationMode>(mode));
    }
    // The names of Webots 8 and before.
    void simulationRevert() { wb_supervisor_simulation_revert(); }
    void simulationPhysicsReset() { wb_supervisor_simulation_physics_reset(); }
    void worldLoad(const std::string &file) { wb_supervisor_world_load(file.c_str()); }
    bool worldSave() { return wb_supervisor_world_save(0); }
    bool worldSave(const std::string &file) { return wb_supervisor_world_save(file.c_str()); }
    void worldReload() { wb_supervisor_world_reload(); }
    void setLabel(int id, const std::string &label, double x, double y, double size, int color,
                  double transparency = 0.0, const std::string &font = "Arial") {
      wb_supervisor_set_label(id, label.c_str(), x, y, size, color, transparency, font.c_str());
    }
    void exportImage(const std::string &file, int quality) const {
      wb_supervisor_export_image(file.c_str(), quality);
    }
    void movieStartRecording(const std::string &file, int width, int height, int codec,
                             int quality, int acceleration, bool caption) const {
      wb_supervisor_movie_start_recording(file.c_str(), width, height, codec, quality,
                                          acceleration, caption);
    }
    void movieStopRecording() { wb_supervisor_movie_stop_recording(); }
    bool movieIsReady() const { return wb_supervisor_movie_is_ready(); }
    bool movieFailed() const { return wb_supervisor_movie_failed(); }
  };
}  // namespace webots

#endif
