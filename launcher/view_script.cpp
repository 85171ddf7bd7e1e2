#include "launcher/view_script.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

namespace cosim::launcher {

namespace {
// A Python string literal (JSON's escapes are Python's).
std::string quoted(const std::string& s) { return nlohmann::json(s).dump(); }

std::string fluid_line(const std::optional<FluidView>& f) {
  if (!f) return "FLUID = None\n";
  const std::string slice = f->dimension == 3 ? fmt::format(",\n         \"slice_origin\": [{}, {}, {}]",
                                                            f->slice_origin[0], f->slice_origin[1], f->slice_origin[2])
                                              : "";
  return fmt::format("FLUID = {{\"file\": {}, \"dimension\": {}, \"pressure\": {}, \"flow_cells\": {}{}}}\n",
                     quoted(f->file), f->dimension, f->pressure.empty() ? "None" : quoted(f->pressure),
                     f->flow_cells ? "True" : "False", slice);
}

std::string solid_line(const std::optional<SolidView>& s) {
  if (!s) return "SOLID = None\n";
  return fmt::format("SOLID = {{\"file\": {}, \"stress\": {}}}\n", quoted(s->file),
                     s->stress.empty() ? "None" : quoted(s->stress));
}

// Everything after the run's values: the same for every run.
constexpr const char* kBody = R"view(
try:
    RUN = os.path.dirname(os.path.abspath(__file__))
except NameError:  # run by a tool that sets no __file__
    RUN = WRITTEN_IN

view = GetActiveViewOrCreate("RenderView")
readers, coloured, lifted = [], [], []


def series(name, file):
    reader = Xdmf3ReaderS(registrationName=name, FileName=[os.path.join(RUN, file)])
    readers.append(reader)
    return reader


def colour_by(display, array, preset, title, place):
    ColorBy(display, ("CELLS", array))
    lut = GetColorTransferFunction(array)
    lut.ApplyPreset(preset, True)
    bar = GetScalarBar(lut, view)
    bar.Title, bar.ComponentTitle = title, ""
    bar.WindowLocation, bar.Orientation = place, "Horizontal"
    bar.RangeLabelFormat = "%.6g"
    display.SetScalarBarVisibility(view, True)
    coloured.append(display)


if FLUID:
    fluid = series("fluid", FLUID["file"])
    shown = fluid
    if FLUID["flow_cells"]:  # the flow cells (embedded_category 0 fluid, 1 fluid-cut), not the bodies' insides
        shown = Threshold(registrationName="fluid flow cells", Input=shown, Scalars=["CELLS", "embedded_category"],
                          LowerThreshold=0, UpperThreshold=1, ThresholdMethod="Between")
    if FLUID["dimension"] == 3:
        shown = Slice(registrationName="fluid mid-plane", Input=shown)
        shown.SliceType = "Plane"
        shown.SliceType.Origin = FLUID["slice_origin"]
        shown.SliceType.Normal = [0.0, 0.0, 1.0]
        shown.Triangulatetheslice = 0
    display = Show(shown, view)
    display.Representation = "Surface"
    if FLUID["pressure"]:
        title = f"fluid {FLUID['pressure']} [Pa]"
        colour_by(display, FLUID["pressure"], "Cool to Warm", title, "Lower Right Corner")
    else:
        ColorBy(display, None)

if SOLID:
    display = Show(series("solid", SOLID["file"]), view)
    display.Representation = "Surface"
    if SOLID["stress"]:
        colour_by(display, SOLID["stress"], "Viridis (matplotlib)", "solid von Mises stress [Pa]",
                  "Upper Right Corner")
    else:
        ColorBy(display, None)
    lifted.append(display)

if INTERFACE:
    display = Show(series("interface", INTERFACE), view)
    display.Representation = "Wireframe"
    ColorBy(display, None)
    display.AmbientColor = display.DiffuseColor = [0.0, 0.0, 0.0]
    display.LineWidth = 3.0
    lifted.append(display)

# A 1D or 2D fluid is a slab one cell thick around z = 0, where a 2D solid lies: the solid and the interface are
# drawn just above the slab.
if FLUID and FLUID["dimension"] < 3:
    fluid.UpdatePipeline()
    top = fluid.GetDataInformation().GetBounds()[5]
    for display in lifted:
        display.Position = [0.0, 0.0, 2.0 * top]
    view.InteractionMode = "2D"

# The last time step of any series, the colour ranges fitted to the data at that time.
times = []
for reader in readers:
    steps = reader.TimestepValues
    times += list(steps) if hasattr(steps, "__len__") else [steps] if steps is not None else []
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
if times:
    scene.AnimationTime = max(times)
clock = Show(AnnotateTime(registrationName="time", Format="t = {time:.6g} s"), view)
clock.WindowLocation = "Upper Left Corner"
Render(view)
for display in coloured:
    display.RescaleTransferFunctionToDataRange(False, True)

view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]
ResetCamera(view)
Render(view)
if os.environ.get("COSIM_VIEW_SCREENSHOT"):
    SaveScreenshot(os.environ["COSIM_VIEW_SCREENSHOT"], view, ImageResolution=[1280, 720],
                   FontScaling="Do not scale fonts")
)view";
}  // namespace

std::string view_script(const RunView& v, const std::filesystem::path& run_dir) {
  std::string what;
  if (v.fluid)
    what += v.fluid->dimension == 3 ? "#   the fluid's pressure on its mid-plane (normal z)\n"
                                    : "#   the fluid coloured by pressure\n";
  if (v.solid) what += "#   the solid's von Mises stress on its deformed mesh\n";
  if (!v.interface_file.empty()) what += "#   the interface faces\n";
  return "# ParaView view of this run (cosim writes it at the end of every run), at the last time step with the\n"
         "# colour ranges fitted to it:\n" +
         what +
         "# Open it with\n"
         "#   paraview --state=view.py                          (cosim view RUN; File > Load State opens it too)\n"
         "#   COSIM_VIEW_SCREENSHOT=view.png pvbatch view.py    a picture of it\n"
         "import os\n\n"
         "from paraview.simple import (AnnotateTime, ColorBy, GetActiveViewOrCreate, GetAnimationScene,\n"
         "                             GetColorTransferFunction, GetScalarBar, Render, ResetCamera, SaveScreenshot, "
         "Show,\n"
         "                             Slice, Threshold, Xdmf3ReaderS)\n\n"
         "# What the run holds: its series (relative to this file) and arrays; None where it has none.\n" +
         fluid_line(v.fluid) + solid_line(v.solid) +
         "INTERFACE = " + (v.interface_file.empty() ? std::string("None") : quoted(v.interface_file)) + "\n" +
         "WRITTEN_IN = " + quoted(run_dir.string()) + "\n" + kBody;
}

}  // namespace cosim::launcher
