/**
 * @file   vtkCausticsSettingMacros.h
 * @brief  VTK's Set/Get macros for a member of a technique's settings struct (not wrapped).
 *
 * A technique keeps its knobs in one plain settings value (caustics::CausticMapSettings,
 * caustics::ScreenSpaceSettings) that its stages take by const reference.
 * vtkCausticsSettingMacro and vtkCausticsSettingClampMacro are vtkSetMacro /
 * vtkSetClampMacro and vtkGetMacro for a member of such a struct, so that the pass
 * keeps VTK's Set/Get API (and its wrapping) over the plain value, and nothing is
 * copied into the stages per frame.
 */
#ifndef vtkCausticsSettingMacros_h
#define vtkCausticsSettingMacros_h

/** vtkSetMacro + vtkGetMacro for member `name` of the settings struct `settings`. */
#define vtkCausticsSettingMacro(settings, name, type)                                              \
  virtual void Set##name(type _arg)                                                                \
  {                                                                                                \
    if (this->settings.name != _arg)                                                               \
    {                                                                                              \
      this->settings.name = _arg;                                                                  \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  virtual type Get##name()                                                                         \
  {                                                                                                \
    return this->settings.name;                                                                    \
  }

/** vtkSetClampMacro + vtkGetMacro for member `name` of the settings struct `settings`. */
#define vtkCausticsSettingClampMacro(settings, name, type, min, max)                               \
  virtual void Set##name(type _arg)                                                                \
  {                                                                                                \
    const type value = _arg < (min) ? (min) : (_arg > (max) ? (max) : _arg);                       \
    if (this->settings.name != value)                                                              \
    {                                                                                              \
      this->settings.name = value;                                                                 \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  virtual type Get##name##MinValue()                                                               \
  {                                                                                                \
    return (min);                                                                                  \
  }                                                                                                \
  virtual type Get##name##MaxValue()                                                               \
  {                                                                                                \
    return (max);                                                                                  \
  }                                                                                                \
  virtual type Get##name()                                                                         \
  {                                                                                                \
    return this->settings.name;                                                                    \
  }

#endif
