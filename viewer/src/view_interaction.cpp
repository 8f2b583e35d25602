// The interactive window: trackball camera, keys, click picking and the scripted events the
// tests use to drive the real interactor (key and mouse events go through the same observers
// as a user's, so the test exercises the bindings themselves).

#include "view_scene.h"

#include "core/error.h"

#include <fmt/format.h>
#include <vtkCallbackCommand.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>

#include <cctype>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

namespace penumbra::viewer {

namespace {

/// Keys and clicks of the viewer on top of VTK's trackball camera (left drag rotates, middle
/// pans, right or wheel zooms). VTK's own key bindings are not forwarded: they clash ('e' and
/// 'q' quit, 's' and 'w' switch representations).
class ViewStyle final : public vtkInteractorStyleTrackballCamera {
public:
    static ViewStyle* New();
    vtkTypeMacro(ViewStyle, vtkInteractorStyleTrackballCamera)

        ViewScene* scene = nullptr;
    std::exception_ptr failure; ///< an error inside a callback, rethrown after the loop

    void OnChar() override {
        guarded([&] { handle_key(); });
    }
    void OnKeyPress() override {}
    void OnLeftButtonDown() override {
        Interactor->GetEventPosition(press_);
        vtkInteractorStyleTrackballCamera::OnLeftButtonDown();
    }
    void OnLeftButtonUp() override {
        vtkInteractorStyleTrackballCamera::OnLeftButtonUp();
        int* p = Interactor->GetEventPosition();
        if (std::abs(p[0] - press_[0]) <= 2 && std::abs(p[1] - press_[1]) <= 2)
            guarded([&] {
                scene->pick(p[0], p[1]);
                Interactor->Render();
            });
    }

private:
    template <typename Fn> void guarded(Fn&& fn) {
        try {
            fn();
        } catch (...) {
            failure = std::current_exception();
            Interactor->TerminateApp();
        }
    }

    void handle_key() {
        vtkRenderWindowInteractor* rwi = Interactor;
        const std::string sym = rwi->GetKeySym() ? rwi->GetKeySym() : "";
        const char key = rwi->GetKeyCode();
        if (sym == "Escape" || key == 'q' || key == 'Q') {
            rwi->TerminateApp();
            return;
        }
        switch (key) {
        case 'a':
            scene->cycle_array(+1);
            break;
        case 'A':
            scene->cycle_array(-1);
            break;
        case 'l':
        case 'L':
            scene->toggle_log();
            break;
        case 'e':
        case 'E':
            scene->toggle_edges();
            break;
        case 'n':
        case 'N':
            scene->change_step(+1);
            break;
        case 'p':
        case 'P':
            scene->change_step(-1);
            break;
        case 'c':
        case 'C':
            scene->scene_camera();
            break;
        case 'r':
        case 'R':
            scene->fit_camera();
            break;
        case 's':
        case 'S':
            scene->toggle_sensors();
            break;
        case 'd':
        case 'D':
            scene->toggle_discontinuities();
            break;
        default:
            return;
        }
        rwi->Render();
    }

    int press_[2] = {0, 0};
};
vtkStandardNewMacro(ViewStyle);

/// Plays the script's events, one per timer tick, through the interactor.
struct ScriptPlayer {
    vtkRenderWindowInteractor* interactor = nullptr;
    const std::vector<std::string>* script = nullptr;
    std::size_t next = 0;
    int timer = -1;

    static void on_timer(vtkObject*, unsigned long, void* client, void*) {
        auto* self = static_cast<ScriptPlayer*>(client);
        if (self->next < self->script->size())
            self->play((*self->script)[self->next++]);
        if (self->next == self->script->size() && self->timer >= 0) {
            self->interactor->DestroyTimer(self->timer);
            self->timer = -1;
        }
    }

    void play(const std::string& event) {
        int x = 0, y = 0;
        if (std::sscanf(event.c_str(), "pick:%d:%d", &x, &y) == 2) {
            interactor->SetEventInformation(x, y, 0, 0);
            interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
            interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
            return;
        }
        const bool escape = event == "Escape";
        const char key = escape ? char(27) : event[0];
        const std::string sym = escape ? "Escape" : event;
        interactor->SetKeyEventInformation(0, std::isupper(static_cast<unsigned char>(key)), key, 1,
                                           sym.c_str());
        interactor->InvokeEvent(vtkCommand::KeyPressEvent);
        interactor->InvokeEvent(vtkCommand::CharEvent);
        interactor->InvokeEvent(vtkCommand::KeyReleaseEvent);
    }
};

void check_script(const std::vector<std::string>& script) {
    for (const std::string& event : script) {
        int x = 0, y = 0;
        const bool pick = std::sscanf(event.c_str(), "pick:%d:%d", &x, &y) == 2;
        if (!pick && event != "Escape" && event.size() != 1)
            throw ConfigError(fmt::format("--script: unknown event '{}' (a key such as 'a', "
                                          "'Escape', or 'pick:X:Y')",
                                          event));
    }
}

} // namespace

void run_window(ViewScene& scene, const std::vector<std::string>& script, const Context& ctx) {
    check_script(script);
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(scene.window());
    vtkNew<ViewStyle> style;
    style->scene = &scene;
    interactor->SetInteractorStyle(style);

    int frames = 0;
    vtkNew<vtkCallbackCommand> count_frames;
    count_frames->SetClientData(&frames);
    count_frames->SetCallback(
        [](vtkObject*, unsigned long, void* client, void*) { ++*static_cast<int*>(client); });
    scene.window()->AddObserver(vtkCommand::EndEvent, count_frames);

    ScriptPlayer player{interactor, &script};
    vtkNew<vtkCallbackCommand> on_timer;
    on_timer->SetClientData(&player);
    on_timer->SetCallback(&ScriptPlayer::on_timer);
    interactor->AddObserver(vtkCommand::TimerEvent, on_timer);

    scene.show_text(true);
    interactor->Initialize();
    scene.render();
    if (!script.empty())
        player.timer = interactor->CreateRepeatingTimer(50);
    interactor->Start();
    scene.window()->RemoveObserver(count_frames);
    scene.window()->Finalize();
    if (style->failure)
        std::rethrow_exception(style->failure);
    ctx.info("view: closed after {} frames", frames);
}

} // namespace penumbra::viewer
