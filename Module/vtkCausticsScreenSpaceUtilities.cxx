#include "vtkCausticsScreenSpaceUtilities.h"

#include "vtkCausticsGLUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <iostream>

namespace caustics
{
namespace ssp
{
namespace
{
void ReportLeak(const char* what)
{
  std::cerr << "vtkCausticsScreenSpaceUtilities: " << what
            << " destroyed before Release(): GL object leaked\n";
}
}

Texture::~Texture()
{
  if (this->Handle)
  {
    ReportLeak("texture");
  }
}

bool Texture::Ensure(int width, int height, int layers, unsigned int internalFormat)
{
  width = width < 1 ? 1 : width;
  height = height < 1 ? 1 : height;
  layers = layers < 0 ? 0 : layers;
  if (this->Handle && this->Width == width && this->Height == height && this->Layers == layers &&
    this->Format == internalFormat)
  {
    return false;
  }
  this->Release();
  glCreateTextures(layers > 0 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D, 1, &this->Handle);
  if (layers > 0)
  {
    glTextureStorage3D(this->Handle, 1, internalFormat, width, height, layers);
  }
  else
  {
    glTextureStorage2D(this->Handle, 1, internalFormat, width, height);
  }
  glTextureParameteri(this->Handle, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(this->Handle, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(this->Handle, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(this->Handle, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  this->Width = width;
  this->Height = height;
  this->Layers = layers;
  this->Format = internalFormat;
  caustics::gl::CountObject(caustics::gl::Counted::Texture, 1, this->Bytes());
  return true;
}

long long Texture::Bytes() const
{
  return static_cast<long long>(this->Width) * this->Height * std::max(1, this->Layers) *
    static_cast<long long>(caustics::gl::BytesPerTexel(this->Format));
}

void Texture::Release()
{
  if (this->Handle)
  {
    glDeleteTextures(1, &this->Handle);
    caustics::gl::CountObject(caustics::gl::Counted::Texture, -1, -this->Bytes());
  }
  this->Handle = 0;
  this->Width = this->Height = this->Layers = 0;
  this->Format = 0;
}

Framebuffer::~Framebuffer()
{
  if (this->Handle)
  {
    ReportLeak("framebuffer");
  }
}

unsigned int Framebuffer::Get()
{
  if (!this->Handle)
  {
    glCreateFramebuffers(1, &this->Handle);
    caustics::gl::CountObject(caustics::gl::Counted::Framebuffer, 1, 0);
  }
  return this->Handle;
}

void Framebuffer::Release()
{
  if (this->Handle)
  {
    glDeleteFramebuffers(1, &this->Handle);
    caustics::gl::CountObject(caustics::gl::Counted::Framebuffer, -1, 0);
  }
  this->Handle = 0;
}

TextureUnits::TextureUnits(vtkOpenGLRenderWindow* renWin)
  : Window(renWin)
{
}

TextureUnits::~TextureUnits()
{
  vtkTextureUnitManager* manager = this->Window->GetTextureUnitManager();
  for (int unit : this->Units)
  {
    glBindTextureUnit(unit, 0);
    manager->Free(unit);
  }
  for (vtkTextureObject* texture : this->Objects)
  {
    texture->Deactivate();
  }
}

int TextureUnits::Bind(unsigned int texture)
{
  const int unit = this->Window->GetTextureUnitManager()->Allocate();
  if (unit < 0)
  {
    return -1;
  }
  glBindTextureUnit(unit, texture);
  this->Units.push_back(unit);
  return unit;
}

int TextureUnits::Bind(vtkTextureObject* texture)
{
  texture->Activate();
  this->Objects.push_back(texture);
  return texture->GetTextureUnit();
}

float PixelScale(const float worldToClip[16], int width, int height)
{
  // Column-major: the clip x row is (m[0], m[4], m[8]), the clip y row (m[1], m[5], m[9]).
  const double sx = std::sqrt(worldToClip[0] * worldToClip[0] + worldToClip[4] * worldToClip[4] +
    worldToClip[8] * worldToClip[8]);
  const double sy = std::sqrt(worldToClip[1] * worldToClip[1] + worldToClip[5] * worldToClip[5] +
    worldToClip[9] * worldToClip[9]);
  const double finest = std::max(width * sx, height * sy);
  return finest > 0.0 ? static_cast<float>(2.0 / finest) : 0.0f;
}

int MaxTextureSize()
{
  GLint size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &size);
  return size;
}
}
}
