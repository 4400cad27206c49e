// Shared by every caustics shader (prepended after #version and the defines).
// Constants and encodings here must match vtkCausticsSceneData.h on the host.

const float CAUSTICS_PI = 3.14159265358979323846;

// Material roles (vtkCausticsMaterial::Role).
const int ROLE_NONE = 0;
const int ROLE_RECEIVER = 1;
const int ROLE_REFLECTOR = 2;
const int ROLE_REFRACTOR = 3;
