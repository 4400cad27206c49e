"""The installed `vtkcaustics` package, used as a Python user would: it must come
from the prefix given as the only argument (PYTHONPATH names nothing else), every
module's classes are there, the built-in scenes find their data in the prefix, and
the factory, the technique registry and the image I/O work from Python.

    PYTHONPATH=PREFIX/lib/python3/dist-packages python3 consumer.py PREFIX
"""
import os
import sys
import tempfile

import vtkcaustics
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLRenderer


def main(prefix):
    where = os.path.realpath(vtkcaustics.__file__)
    if not where.startswith(os.path.realpath(prefix) + os.sep):
        return "vtkcaustics comes from %s, not from %s" % (where, prefix)
    for name in ("vtkCausticsMaterial", "vtkCausticsRenderPass", "vtkCausticsBuiltinScene",
                 "vtkCausticsReferenceRenderer", "vtkCausticsEGLRenderWindow"):
        if not hasattr(vtkcaustics, name):
            return "the package has no " + name

    bunny = vtkcaustics.vtkCausticsBuiltinScene()
    bunny.SetSceneName("bunny")
    if not bunny.Populate(vtkOpenGLRenderer()):
        return "the bunny finds no data: " + bunny.GetLastError()

    factory = vtkcaustics.vtkCausticsWindowFactory()
    window = factory.NewWindow(True)
    if window is None:
        return "no window: " + factory.GetLastError()
    window.SetMultiSamples(0)
    window.SetSize(48, 48)
    renderer = vtkOpenGLRenderer()
    window.AddRenderer(renderer)
    scene = vtkcaustics.vtkCausticsBuiltinScene()
    scene.SetSceneName("ball-lens")
    scene.Populate(renderer)
    caustics = vtkcaustics.vtkCausticsTechniques.NewPass("best")
    caustics.KeepBuffersOn()
    caustics.SetLightBufferResolution(64)
    renderer.SetPass(caustics)
    window.Render()
    image = vtkImageData()
    if not caustics.ReadBuffer("FinalColor", image):
        return "the %s pass made no picture" % vtkcaustics.vtkCausticsTechniques.GetBestName()
    image.GetPointData().GetArray(0).SetName("FinalColor")
    renderer.SetPass(None)
    caustics.ReleaseGraphicsResources(window)

    io = vtkcaustics.vtkCausticsImageIO()
    with tempfile.TemporaryDirectory() as folder:
        exr = os.path.join(folder, "consumer.exr")
        if not io.WriteEXRFile(image, ["FinalColor"], [""], exr):
            return io.GetLastError()
        back = io.ReadEXRFile(exr)
        if back is None or back.GetDimensions() != image.GetDimensions():
            return "the EXR did not read back: " + io.GetLastError()
    print("consumer.py: ok (vtkcaustics from %s, window %s)"
          % (os.path.dirname(where), factory.GetLastPath()))
    return None


if __name__ == "__main__":
    problem = main(sys.argv[1])
    if problem:
        print("consumer.py: " + problem)
        sys.exit(1)
