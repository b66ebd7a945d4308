// The OpenGL functions Sylva calls, loaded at run time from the current backend (core/gl/
// gl_context.h) instead of linked. Both backends' libraries export gl* symbols (libOSMesa its
// own, libOpenGL GLVND's dispatch), and a direct call goes to whichever the linker found first:
// with the other backend current it silently does nothing (DEPENDENCIES.md, "Headless EGL").
// So no file includes a GL header with GL_GLEXT_PROTOTYPES: <GL/glcorearb.h> gives the types
// and constants only, and each function below is a per-thread pointer of the same name in
// namespace sylva, set by GlContext::make_current() from the table its backend filled through
// OSMesaGetProcAddress or eglGetProcAddress. Code in namespace sylva calls glDrawElements(...)
// as usual; a gl* function missing from the list does not compile (no prototype), so nothing can
// reach a library's export by accident.
//
// Why a hand-kept list and not a loader library: libepoxy (Debian's) picks its dispatch by
// probing GLX/EGL itself and aborts with OSMesa; glad is not packaged in Debian 12 and would
// bring a generator for ~80 functions. The list is the functions core/gl uses; add one here
// when a new call needs it (the compiler says so).
#pragma once

#include <GL/glcorearb.h>

#include <string>

#include "core/gl/gl_context.h"

namespace sylva {

// X(pointer type, name) for every GL function Sylva calls.
#define SYLVA_GL_FUNCTIONS(X)                                                        \
  X(PFNGLACTIVETEXTUREPROC, glActiveTexture)                                         \
  X(PFNGLATTACHSHADERPROC, glAttachShader)                                           \
  X(PFNGLBINDBUFFERPROC, glBindBuffer)                                               \
  X(PFNGLBINDBUFFERBASEPROC, glBindBufferBase)                                       \
  X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                                     \
  X(PFNGLBINDTEXTUREPROC, glBindTexture)                                             \
  X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                                     \
  X(PFNGLBUFFERDATAPROC, glBufferData)                                               \
  X(PFNGLBUFFERSTORAGEPROC, glBufferStorage)                                         \
  X(PFNGLBUFFERSUBDATAPROC, glBufferSubData)                                         \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)                       \
  X(PFNGLCLEARBUFFERFVPROC, glClearBufferfv)                                         \
  X(PFNGLCLEARBUFFERUIVPROC, glClearBufferuiv)                                       \
  X(PFNGLCOMPILESHADERPROC, glCompileShader)                                         \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                                         \
  X(PFNGLCREATESHADERPROC, glCreateShader)                                           \
  X(PFNGLCULLFACEPROC, glCullFace)                                                   \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                                         \
  X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                               \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                                         \
  X(PFNGLDELETESHADERPROC, glDeleteShader)                                           \
  X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                                       \
  X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)                               \
  X(PFNGLDEPTHFUNCPROC, glDepthFunc)                                                 \
  X(PFNGLDEPTHMASKPROC, glDepthMask)                                                 \
  X(PFNGLDISABLEPROC, glDisable)                                                     \
  X(PFNGLDISABLEVERTEXATTRIBARRAYPROC, glDisableVertexAttribArray)                   \
  X(PFNGLDRAWBUFFERSPROC, glDrawBuffers)                                             \
  X(PFNGLDRAWELEMENTSPROC, glDrawElements)                                           \
  X(PFNGLDRAWELEMENTSINSTANCEDPROC, glDrawElementsInstanced)                         \
  X(PFNGLDRAWELEMENTSINSTANCEDBASEINSTANCEPROC, glDrawElementsInstancedBaseInstance) \
  X(PFNGLENABLEPROC, glEnable)                                                       \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray)                     \
  X(PFNGLFINISHPROC, glFinish)                                                       \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D)                           \
  X(PFNGLFRONTFACEPROC, glFrontFace)                                                 \
  X(PFNGLGENBUFFERSPROC, glGenBuffers)                                               \
  X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                                     \
  X(PFNGLGENTEXTURESPROC, glGenTextures)                                             \
  X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                                     \
  X(PFNGLGENERATEMIPMAPPROC, glGenerateMipmap)                                       \
  X(PFNGLGETERRORPROC, glGetError)                                                   \
  X(PFNGLGETINTEGERVPROC, glGetIntegerv)                                             \
  X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                                 \
  X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                                           \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                                   \
  X(PFNGLGETSHADERIVPROC, glGetShaderiv)                                             \
  X(PFNGLGETSTRINGPROC, glGetString)                                                 \
  X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)                               \
  X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                             \
  X(PFNGLPIXELSTOREIPROC, glPixelStorei)                                             \
  X(PFNGLREADBUFFERPROC, glReadBuffer)                                               \
  X(PFNGLREADPIXELSPROC, glReadPixels)                                               \
  X(PFNGLSHADERSOURCEPROC, glShaderSource)                                           \
  X(PFNGLTEXPARAMETERIPROC, glTexParameteri)                                         \
  X(PFNGLTEXSTORAGE2DPROC, glTexStorage2D)                                           \
  X(PFNGLTEXSUBIMAGE2DPROC, glTexSubImage2D)                                         \
  X(PFNGLUNIFORM1FPROC, glUniform1f)                                                 \
  X(PFNGLUNIFORM1FVPROC, glUniform1fv)                                               \
  X(PFNGLUNIFORM1IPROC, glUniform1i)                                                 \
  X(PFNGLUNIFORM1UIPROC, glUniform1ui)                                               \
  X(PFNGLUNIFORM2FPROC, glUniform2f)                                                 \
  X(PFNGLUNIFORM2FVPROC, glUniform2fv)                                               \
  X(PFNGLUNIFORM2IPROC, glUniform2i)                                                 \
  X(PFNGLUNIFORM3FVPROC, glUniform3fv)                                               \
  X(PFNGLUNIFORM4FPROC, glUniform4f)                                                 \
  X(PFNGLUNIFORM4FVPROC, glUniform4fv)                                               \
  X(PFNGLUNIFORMMATRIX3FVPROC, glUniformMatrix3fv)                                   \
  X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv)                                   \
  X(PFNGLUSEPROGRAMPROC, glUseProgram)                                               \
  X(PFNGLVERTEXATTRIB1FPROC, glVertexAttrib1f)                                       \
  X(PFNGLVERTEXATTRIB2FPROC, glVertexAttrib2f)                                       \
  X(PFNGLVERTEXATTRIB3FPROC, glVertexAttrib3f)                                       \
  X(PFNGLVERTEXATTRIB4FPROC, glVertexAttrib4f)                                       \
  X(PFNGLVERTEXATTRIBDIVISORPROC, glVertexAttribDivisor)                             \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, glVertexAttribIPointer)                           \
  X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer)                             \
  X(PFNGLVIEWPORTPROC, glViewport)

// The functions of one context, as its backend's GetProcAddress gave them.
struct GlApi {
#define SYLVA_GL_MEMBER(type, name) type name = nullptr;
  SYLVA_GL_FUNCTIONS(SYLVA_GL_MEMBER)
#undef SYLVA_GL_MEMBER
};

// Fills every entry through `get_proc` (OSMesaGetProcAddress, eglGetProcAddress: called with
// "glDrawElements", ...); returns the names it left null, space-separated ("" when all were
// found).
std::string load_gl_api(GlApi& api, GlGetProc get_proc);

// What this thread's gl* names call: `api`'s functions, or (nullptr) stubs that stop the
// program with a message naming the call (a GL call with no Sylva context current is a bug).
void use_gl_api(const GlApi* api);

// Throws std::runtime_error when the current context recorded an error since the last check:
// "<what>: the GL ran out of memory" (a GPU with less memory than the frame or scene needs) or
// the error's code. Nothing is drawn or read right after an error, so it must not pass silently.
void check_gl_errors(const std::string& what);

// The per-thread pointers the gl* names are, constant-initialised to the stubs.
#define SYLVA_GL_DECLARE(type, name) extern thread_local constinit type name;
SYLVA_GL_FUNCTIONS(SYLVA_GL_DECLARE)
#undef SYLVA_GL_DECLARE

}  // namespace sylva
