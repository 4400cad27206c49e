"""VTK caustics module: physically based surface and volume caustics as VTK render passes.

Import after VTK's OpenGL2 rendering module, whose classes the passes derive from.
"""
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (base classes, OpenGL factory)
from .vtkCausticsScene import *  # noqa: F401,F403
from .vtkRenderingCaustics import *  # noqa: F401,F403
from .vtkIOCaustics import *  # noqa: F401,F403
from .vtkCausticsReference import *  # noqa: F401,F403
from .vtkRenderingCausticsEGL import *  # noqa: F401,F403
from .vtkRenderingCausticsCPU import *  # noqa: F401,F403

# The CPU technique lives in its own module (it links Embree, the passes must not):
# make it known by name, as the command-line tools do.
vtkCausticsProgressivePhotonPass.RegisterTechnique()
