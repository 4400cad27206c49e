"""The Python wrapping: a built-in scene renders through the caustics pass from
Python, buffers read back, bad input is refused as in C++, and the technique
registry, the window factory and the image I/O are callable."""
import os
import sys
import tempfile

import vtkmodules.vtkInteractionStyle  # noqa: F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderWindow
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer

import vtkcaustics


def main():
    renderer = vtkOpenGLRenderer()
    scene = vtkcaustics.vtkCausticsBuiltinScene()
    scene.SetSceneName("ball-lens")
    if not scene.Populate(renderer):
        return "ball-lens did not populate: " + scene.GetLastError()
    bad = vtkcaustics.vtkCausticsBuiltinScene()
    bad.GlobalWarningDisplayOff()
    bad.SetSceneName("teapot")
    if bad.Populate(vtkOpenGLRenderer()) or "teapot" not in bad.GetLastError():
        return "an unknown scene was not refused"

    caustics = vtkcaustics.vtkCausticsRenderPass()
    caustics.KeepBuffersOn()
    caustics.ComputeDirectIrradianceOn()
    renderer.SetPass(caustics)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(64, 64)
    window.AddRenderer(renderer)
    window.Render()

    direct = vtkImageData()
    if not caustics.ReadBuffer("DirectIrradiance", direct):
        return "no DirectIrradiance buffer"
    values = direct.GetPointData().GetArray(0)
    peak = max(values.GetComponent(i, 0) for i in range(values.GetNumberOfTuples()))
    # The floor faces the 1 W/m^2 light: the brightest pixel receives 1 W/m^2.
    if abs(peak - 1.0) > 1e-4:
        return "peak direct irradiance %g W/m^2, expected 1" % peak
    if vtkcaustics.vtkCausticsMaterial.GetRoleName(3) != "refractor":
        return "role names are wrong"
    if caustics.GetLastFrameLostLightBound() != -1.0:
        return "the base pass, which traces no photon, gave a lost-light bound"
    renderer.SetPass(None)
    caustics.ReleaseGraphicsResources(window)

    # Each technique renders from Python. The ball lens (radius 1, n = 1.5) focuses
    # the 1 W/m^2 light 1.5 m above the floor, so the ~2.8 W it transmits spread
    # again over a disk of ~1 m radius on the floor: a caustic of ~0.9 W/m^2 and
    # more. 128^2 pixels: at 64^2 the ball spans too few pixels for the
    # screen-space tracer's layers.
    window.SetSize(128, 128)
    for technique in (vtkcaustics.vtkCausticsScreenSpacePhotonPass,
                      vtkcaustics.vtkCausticsHierarchicalCausticMapPass):
        name = technique.__name__
        pass_ = technique()
        pass_.KeepBuffersOn()
        pass_.SetLightBufferResolution(128)
        renderer.SetPass(pass_)
        window.Render()
        caustic = vtkImageData()
        if not pass_.ReadBuffer("CausticIrradiance", caustic):
            return name + ": no CausticIrradiance buffer"
        values = caustic.GetPointData().GetArray(0)
        peak = max(values.GetComponent(i, 0) for i in range(values.GetNumberOfTuples()))
        if not 0.5 < peak < 10.0:
            return "%s: peak caustic irradiance %g W/m^2, expected 0.5..10" % (name, peak)
        # The light it lost (docs/accuracy.md): the ball lens loses almost none.
        lost = pass_.GetLastFrameLostLightBound()
        if not 0.0 <= lost < 0.05:
            return "%s: lost-light bound %g on the ball lens, expected 0..0.05" % (name, lost)
        # A still view's mean (ProgressiveFrames) grows a frame at a time; its
        # textures are released with the pass's (the bookkeeping below).
        pass_.SetProgressiveFrames(3)
        for frame in range(1, 4):
            window.Render()
            if pass_.GetFramesAveraged() != frame:
                return "%s: frame %d holds the mean of %d" % (
                    name, frame, pass_.GetFramesAveraged())
        # The GPU bookkeeping (vtkCausticsRenderPass.GetGraphicsMemory in C++).
        if vtkcaustics.vtkCausticsRenderPass.GetGraphicsObjects() <= 0 or \
                vtkcaustics.vtkCausticsRenderPass.GetGraphicsBytes() <= 0:
            return name + ": the GPU bookkeeping counted nothing after a frame"
        renderer.SetPass(None)
        pass_.ReleaseGraphicsResources(window)
        if vtkcaustics.vtkCausticsRenderPass.GetGraphicsObjects() != 0:
            return name + ": GPU objects left after ReleaseGraphicsResources"
    return check_registry_factory_and_io()


def check_registry_factory_and_io():
    """The technique registry, the window factory and the EXR/PNG I/O from Python
    (their C++ functions take std::string* or return vtkSmartPointer, which the
    wrapping cannot: these are the wrappable forms)."""
    techniques = vtkcaustics.vtkCausticsTechniques
    if techniques.GetBestName() not in techniques.GetNames():
        return "the best technique is not a registered one"
    for name in techniques.GetNames() + ("best",):
        pass_ = techniques.NewPass(name)
        if not pass_ or not pass_.IsA("vtkCausticsRenderPass"):
            return "NewPass(%r) made no pass" % name
        if pass_.GetReferenceCount() != 1:
            return "NewPass(%r) leaks a reference" % name
    if techniques.NewPass("magic") is not None:
        return "an unknown technique made a pass"
    problem = check_paraview_technique_list(techniques.GetNames())
    if problem:
        return problem

    factory = vtkcaustics.vtkCausticsWindowFactory()
    window = factory.NewWindow(True)
    if window is None or factory.GetLastPath() != "x11" or factory.GetLastError():
        return "the factory under Xvfb: %r, %r" % (factory.GetLastPath(), factory.GetLastError())

    with tempfile.TemporaryDirectory() as folder:
        return check_image_io(folder)


def check_paraview_technique_list(registered):
    """The ParaView plugin's technique menu (CausticsParaView.xml) offers every
    technique of VTK::RenderingCaustics and nothing unknown. It is plain XML that
    no build reads, so a new technique is easily forgotten there (cascaded was)."""
    import xml.etree.ElementTree as ElementTree

    xml = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                       "ParaView", "Plugin", "CausticsParaView.xml")
    menu = ElementTree.parse(xml).find(
        ".//StringVectorProperty[@name='CausticsTechnique']/StringListDomain")
    if menu is None:
        return "CausticsParaView.xml has no CausticsTechnique list"
    offered = {entry.get("value") for entry in menu.findall("String")}
    # cpu-progressive is registered by VTK::CausticsCPU, which the plugin does not link.
    other_modules = {"cpu-progressive"}
    missing = [name for name in registered if name not in offered | other_modules]
    unknown = sorted(offered - set(registered) - {"best", "off"})
    if missing or unknown:
        return "the ParaView plugin's technique list: missing %s, unknown %s" % (missing, unknown)
    return None


def check_image_io(folder):
    image = vtkImageData()
    image.SetDimensions(4, 2, 1)
    values = vtkFloatArray()
    values.SetName("Irradiance")
    values.SetNumberOfComponents(3)
    for i in range(8):
        values.InsertNextTuple3(i, 2 * i, 0.5)
    image.GetPointData().AddArray(values)
    io = vtkcaustics.vtkCausticsImageIO()
    exr = os.path.join(folder, "wrapping.exr")
    if not io.WriteEXRFile(image, ["Irradiance"], ["caustic"], exr):
        return "WriteEXRFile: " + io.GetLastError()
    back = io.ReadEXRFile(exr)
    if back is None or back.GetPointData().GetArray("caustic").GetTuple3(7) != (7.0, 14.0, 0.5):
        return "ReadEXRFile did not read back what was written: " + io.GetLastError()
    if not io.WritePNGFile(image, "Irradiance", os.path.join(folder, "wrapping.png"), 0.1, True):
        return "WritePNGFile: " + io.GetLastError()
    if io.WriteEXRFile(image, ["Missing"], ["x"], exr) or "Missing" not in io.GetLastError():
        return "a missing array was not refused with its name"
    if io.ReadEXRFile(os.path.join(folder, "none.exr")) is not None or not io.GetLastError():
        return "a missing file was not refused"
    return None


if __name__ == "__main__":
    problem = main()
    if problem:
        print("TestWrapping: " + problem)
        sys.exit(1)
    print("TestWrapping: ok")
