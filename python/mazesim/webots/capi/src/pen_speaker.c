/* Webots' Pen and Speaker functions (reference manual, Pen and Speaker pages): calls served by
   the Python Pen and Speaker, so that a C controller's pen and sounds behave as a Python
   one's (nothing is drawn or heard; a sound plays for its file's duration). */
#include <stddef.h>

#include <webots/pen.h>
#include <webots/speaker.h>

#include "call.h"
#include "link.h"

void wb_pen_write(WbDeviceTag tag, bool write) {
  if (link_device(tag, "wb_pen_write"))
    call_device_set_int("wb_pen_write", tag, write);
}

void wb_pen_set_ink_color(WbDeviceTag tag, int color, double density) {
  if (!link_device(tag, "wb_pen_set_ink_color"))
    return;
  call_begin("wb_pen_set_ink_color");
  call_int(tag);
  call_int(color);
  call_double(density);
  call_end();
}

void wb_speaker_play_sound(WbDeviceTag left, WbDeviceTag right, const char *sound, double volume,
                           double pitch, double balance, bool loop) {
  link_start();
  call_begin("wb_speaker_play_sound");
  call_int(left);
  call_int(right);
  call_text(sound);
  call_double(volume);
  call_double(pitch);
  call_double(balance);
  call_int(loop);
  call_end();
}

/* A call of `function` on the speaker `tag` with a text (NULL: none); its answer's count. */
static int speaker_text_call(const char *function, WbDeviceTag tag, const char *text) {
  if (!link_device(tag, function))
    return 0;
  call_begin(function);
  call_int(tag);
  call_text(text);
  return call_end();
}

void wb_speaker_stop(WbDeviceTag tag, const char *sound) {
  speaker_text_call("wb_speaker_stop", tag, sound);
}

bool wb_speaker_is_sound_playing(WbDeviceTag tag, const char *sound) {
  return speaker_text_call("wb_speaker_is_sound_playing", tag, sound) && answer_int(0);
}

bool wb_speaker_set_engine(WbDeviceTag tag, const char *engine) {
  return speaker_text_call("wb_speaker_set_engine", tag, engine) && answer_int(0);
}

bool wb_speaker_set_language(WbDeviceTag tag, const char *language) {
  return speaker_text_call("wb_speaker_set_language", tag, language) && answer_int(0);
}

/* The text `function` answers for the speaker `tag`, kept until its next such call. */
static const char *speaker_text(const char *function, WbDeviceTag tag) {
  if (!link_device(tag, function))
    return NULL;
  call_begin(function);
  call_int(tag);
  return call_end() ? answer_kept_text(0, function, tag) : NULL;
}

const char *wb_speaker_get_engine(WbDeviceTag tag) {
  return speaker_text("wb_speaker_get_engine", tag);
}

const char *wb_speaker_get_language(WbDeviceTag tag) {
  return speaker_text("wb_speaker_get_language", tag);
}

void wb_speaker_speak(WbDeviceTag tag, const char *text, double volume) {
  if (!link_device(tag, "wb_speaker_speak"))
    return;
  call_begin("wb_speaker_speak");
  call_int(tag);
  call_text(text);
  call_double(volume);
  call_end();
}

bool wb_speaker_is_speaking(WbDeviceTag tag) {
  return link_device(tag, "wb_speaker_is_speaking") &&
         call_device_int("wb_speaker_is_speaking", tag);
}
