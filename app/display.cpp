#include "display.h"

#include <stdexcept>
#include <string>

#include "shaders.h"  // generated from shaders/ at configure time

namespace edacrt::app {
namespace {

GLuint compile(GLenum type, const char* source, const char* name) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("shader ") + name + ": " + log);
    }
    return shader;
}

GLuint make_texture() {
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    // Nearest: one image pixel stays one block of screen pixels (heat maps are per pixel).
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

}  // namespace

Display::Display() {
    const GLuint vs = compile(GL_VERTEX_SHADER, kDisplayVertexShader, "display.vert");
    const GLuint fs = compile(GL_FRAGMENT_SHADER, kDisplayFragmentShader, "display.frag");
    program_ = glCreateProgram();
    glAttachShader(program_, vs);
    glAttachShader(program_, fs);
    glLinkProgram(program_);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program_, GL_LINK_STATUS, &ok);
    if (!ok) throw std::runtime_error("display shaders do not link");
    glGenVertexArrays(1, &vertex_array_);  // core profile: a bound VAO even without attributes
    render_texture_ = make_texture();
    heat_texture_ = make_texture();
    tint_texture_ = make_texture();
}

Display::~Display() {
    glDeleteTextures(1, &render_texture_);
    glDeleteTextures(1, &heat_texture_);
    glDeleteTextures(1, &tint_texture_);
    glDeleteVertexArrays(1, &vertex_array_);
    glDeleteProgram(program_);
}

void Display::upload_render(const Image& image) {
    glBindTexture(GL_TEXTURE_2D, render_texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, image.width, image.height, 0, GL_RGB, GL_FLOAT,
                 image.pixels.data());
}

void Display::upload_heat(const std::vector<float>& values, int width, int height) {
    glBindTexture(GL_TEXTURE_2D, heat_texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, values.data());
}

void Display::upload_tint(const std::vector<float>& values, int width, int height) {
    glBindTexture(GL_TEXTURE_2D, tint_texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, values.data());
}

void Display::draw_tint() const {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(program_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tint_texture_);
    glUniform1i(glGetUniformLocation(program_, "image"), 0);
    glUniform1i(glGetUniformLocation(program_, "mode"), 2);
    glBindVertexArray(vertex_array_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_BLEND);
}

void Display::draw(bool heat, const Tone& tone, float heat_max, bool heat_log,
                   bool difference) const {
    glUseProgram(program_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, heat ? heat_texture_ : render_texture_);
    glUniform1i(glGetUniformLocation(program_, "image"), 0);
    glUniform1i(glGetUniformLocation(program_, "mode"), heat ? (difference ? 3 : 1) : 0);
    glUniform1f(glGetUniformLocation(program_, "exposure"), tone.exposure);
    glUniform1i(glGetUniformLocation(program_, "tone_map"), int(tone.tone_map));
    glUniform1f(glGetUniformLocation(program_, "heat_max"), heat_max);
    glUniform1i(glGetUniformLocation(program_, "heat_log"), heat_log ? 1 : 0);
    glBindVertexArray(vertex_array_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
}

}  // namespace edacrt::app
