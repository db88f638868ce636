// The GL entry points the backend uses, loaded through the app's getProcAddress. One X-macro table so
// that the list of what we depend on is in one place and a missing function is named at createDevice.
#pragma once

#include <GL/glcorearb.h>

#include <string>

#include "bricklight/rhi_gl.h"

// GL 4.6 / EXT_texture_filter_anisotropic tokens (same values), absent from older glcorearb.h.
#ifndef GL_TEXTURE_MAX_ANISOTROPY
#define GL_TEXTURE_MAX_ANISOTROPY 0x84FE
#define GL_MAX_TEXTURE_MAX_ANISOTROPY 0x84FF
#endif

namespace bricklight::gl::detail {

#define BL_GL_FUNCTIONS(X)                                                                                  \
    X(PFNGLGETSTRINGPROC, GetString)                                                                        \
    X(PFNGLGETSTRINGIPROC, GetStringi)                                                                      \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                                                    \
    X(PFNGLGETINTEGER64VPROC, GetInteger64v)                                                                \
    X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v)                                                                \
    X(PFNGLGETFLOATVPROC, GetFloatv)                                                                        \
    X(PFNGLGETERRORPROC, GetError)                                                                          \
    X(PFNGLGETINTERNALFORMATIVPROC, GetInternalformativ)                                                    \
    X(PFNGLENABLEPROC, Enable)                                                                              \
    X(PFNGLDISABLEPROC, Disable)                                                                            \
    X(PFNGLENABLEIPROC, Enablei)                                                                            \
    X(PFNGLDISABLEIPROC, Disablei)                                                                          \
    X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                                                                \
    X(PFNGLNAMEDBUFFERSTORAGEPROC, NamedBufferStorage)                                                      \
    X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                                                      \
    X(PFNGLCOPYNAMEDBUFFERSUBDATAPROC, CopyNamedBufferSubData)                                              \
    X(PFNGLCLEARNAMEDBUFFERSUBDATAPROC, ClearNamedBufferSubData)                                            \
    X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)                                                \
    X(PFNGLGETNAMEDBUFFERPARAMETERI64VPROC, GetNamedBufferParameteri64v)                                    \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                                                \
    X(PFNGLFENCESYNCPROC, FenceSync)                                                                        \
    X(PFNGLCLIENTWAITSYNCPROC, ClientWaitSync)                                                              \
    X(PFNGLDELETESYNCPROC, DeleteSync)                                                                      \
    X(PFNGLISBUFFERPROC, IsBuffer)                                                                          \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                                                      \
    X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange)                                                            \
    X(PFNGLCREATETEXTURESPROC, CreateTextures)                                                              \
    X(PFNGLGENTEXTURESPROC, GenTextures)                                                                    \
    X(PFNGLTEXTUREVIEWPROC, TextureView)                                                                    \
    X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                                                          \
    X(PFNGLTEXTURESTORAGE3DPROC, TextureStorage3D)                                                          \
    X(PFNGLTEXTURESUBIMAGE2DPROC, TextureSubImage2D)                                                        \
    X(PFNGLTEXTURESUBIMAGE3DPROC, TextureSubImage3D)                                                        \
    X(PFNGLGETTEXTURESUBIMAGEPROC, GetTextureSubImage)                                                      \
    X(PFNGLCLEARTEXIMAGEPROC, ClearTexImage)                                                                \
    X(PFNGLCOPYIMAGESUBDATAPROC, CopyImageSubData)                                                          \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                                              \
    X(PFNGLISTEXTUREPROC, IsTexture)                                                                        \
    X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                                                            \
    X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)                                                          \
    X(PFNGLBINDIMAGETEXTURESPROC, BindImageTextures)                                                        \
    X(PFNGLGETTEXTUREPARAMETERIVPROC, GetTextureParameteriv)                                                \
    X(PFNGLGETTEXTURELEVELPARAMETERIVPROC, GetTextureLevelParameteriv)                                      \
    X(PFNGLCREATESAMPLERSPROC, CreateSamplers)                                                              \
    X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)                                                        \
    X(PFNGLSAMPLERPARAMETERFPROC, SamplerParameterf)                                                        \
    X(PFNGLSAMPLERPARAMETERFVPROC, SamplerParameterfv)                                                      \
    X(PFNGLDELETESAMPLERSPROC, DeleteSamplers)                                                              \
    X(PFNGLBINDSAMPLERPROC, BindSampler)                                                                    \
    X(PFNGLCREATESHADERPROC, CreateShader)                                                                  \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                                                                  \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                                                                \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                                                    \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                                          \
    X(PFNGLDELETESHADERPROC, DeleteShader)                                                                  \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                                \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                                                  \
    X(PFNGLDETACHSHADERPROC, DetachShader)                                                                  \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                                                    \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                                  \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                                        \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                                                \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                                                      \
    X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                                                      \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                                      \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                                            \
    X(PFNGLENABLEVERTEXARRAYATTRIBPROC, EnableVertexArrayAttrib)                                            \
    X(PFNGLVERTEXARRAYATTRIBFORMATPROC, VertexArrayAttribFormat)                                            \
    X(PFNGLVERTEXARRAYATTRIBIFORMATPROC, VertexArrayAttribIFormat)                                          \
    X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, VertexArrayAttribBinding)                                          \
    X(PFNGLVERTEXARRAYBINDINGDIVISORPROC, VertexArrayBindingDivisor)                                        \
    X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, VertexArrayVertexBuffer)                                            \
    X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, VertexArrayElementBuffer)                                          \
    X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                                                      \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                                      \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                                            \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)                                            \
    X(PFNGLNAMEDFRAMEBUFFERTEXTURELAYERPROC, NamedFramebufferTextureLayer)                                  \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers)                                    \
    X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer)                                      \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus)                                    \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)                                            \
    X(PFNGLCLEARNAMEDFRAMEBUFFERUIVPROC, ClearNamedFramebufferuiv)                                          \
    X(PFNGLCLEARNAMEDFRAMEBUFFERIVPROC, ClearNamedFramebufferiv)                                            \
    X(PFNGLINVALIDATENAMEDFRAMEBUFFERDATAPROC, InvalidateNamedFramebufferData)                              \
    X(PFNGLVIEWPORTINDEXEDFPROC, ViewportIndexedf)                                                          \
    X(PFNGLSCISSORINDEXEDPROC, ScissorIndexed)                                                              \
    X(PFNGLDEPTHRANGEINDEXEDPROC, DepthRangeIndexed)                                                        \
    X(PFNGLCLIPCONTROLPROC, ClipControl)                                                                    \
    X(PFNGLFRONTFACEPROC, FrontFace)                                                                        \
    X(PFNGLCULLFACEPROC, CullFace)                                                                          \
    X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                                                \
    X(PFNGLPOLYGONMODEPROC, PolygonMode)                                                                    \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                                                        \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                                                        \
    X(PFNGLCOLORMASKIPROC, ColorMaski)                                                                      \
    X(PFNGLBLENDFUNCSEPARATEIPROC, BlendFuncSeparatei)                                                      \
    X(PFNGLBLENDEQUATIONSEPARATEIPROC, BlendEquationSeparatei)                                              \
    X(PFNGLPROVOKINGVERTEXPROC, ProvokingVertex)                                                            \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                                                    \
    X(PFNGLLINEWIDTHPROC, LineWidth)                                                                        \
    X(PFNGLDRAWARRAYSINSTANCEDBASEINSTANCEPROC, DrawArraysInstancedBaseInstance)                            \
    X(PFNGLDRAWELEMENTSINSTANCEDBASEVERTEXBASEINSTANCEPROC, DrawElementsInstancedBaseVertexBaseInstance)    \
    X(PFNGLDRAWARRAYSINDIRECTPROC, DrawArraysIndirect)                                                      \
    X(PFNGLDRAWELEMENTSINDIRECTPROC, DrawElementsIndirect)                                                  \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                                                            \
    X(PFNGLDISPATCHCOMPUTEINDIRECTPROC, DispatchComputeIndirect)                                            \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                                                                \
    X(PFNGLDEBUGMESSAGECALLBACKPROC, DebugMessageCallback)                                                  \
    X(PFNGLDEBUGMESSAGECONTROLPROC, DebugMessageControl)                                                    \
    X(PFNGLPUSHDEBUGGROUPPROC, PushDebugGroup)                                                              \
    X(PFNGLPOPDEBUGGROUPPROC, PopDebugGroup)                                                                \
    X(PFNGLOBJECTLABELPROC, ObjectLabel)                                                                    \
    X(PFNGLGENQUERIESPROC, GenQueries)                                                                      \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)                                                                \
    X(PFNGLQUERYCOUNTERPROC, QueryCounter)                                                                  \
    X(PFNGLGETQUERYIVPROC, GetQueryiv)                                                                      \
    X(PFNGLGETQUERYOBJECTIVPROC, GetQueryObjectiv)                                                          \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                                                    \
    X(PFNGLFLUSHPROC, Flush)                                                                                \
    X(PFNGLFINISHPROC, Finish)

struct Functions {
#define BL_GL_DECLARE(type, name) type name = nullptr;
    BL_GL_FUNCTIONS(BL_GL_DECLARE)
#undef BL_GL_DECLARE

    // Loads every entry point; returns false and names the missing ones in *error.
    bool load(GetProcAddress getProcAddress, std::string* error);
};

}  // namespace bricklight::gl::detail
