/* Calls of mazesim's API that a controller waits for: the function's name and typed values go
   over the link (after the commands queued so far, so that they keep their order), mazesim
   runs the function on the robot's Python objects (see mazesim/webots/native_calls.py) and
   answers typed values. The radio, the display and the supervisor work this way, so that a C
   controller shares their semantics with a Python one. */
#ifndef MAZESIM_CALL_H
#define MAZESIM_CALL_H

/* The types of values (an i32 before each value). */
enum { VALUE_NONE = 0, VALUE_INT = 1, VALUE_DOUBLE = 2, VALUE_BYTES = 3, VALUE_DOUBLES = 4 };

/* Starts a call of `function` (a Webots C function's name). */
void call_begin(const char *function);
void call_int(int value);
void call_double(double value);
void call_bytes(const void *data, int size);
/* A text without its NUL; NULL is no value. */
void call_text(const char *text);
void call_doubles(const double *values, int count);
/* Sends the call, waits for the answer and returns how many values it holds. The values stay
   readable until the next call. */
int call_end(void);

int answer_type(int index);
/* An integer value (a double is truncated; no value is 0). */
int answer_int(int index);
/* A number (no value is NaN). */
double answer_double(int index);
/* Bytes (NULL for no value) and their size. */
const void *answer_bytes(int index, int *size);
/* Numbers (NULL for no value) and their count. */
const double *answer_doubles(int index, int *count);
/* A copy of a text value, ending with a NUL, that the caller frees (NULL for no value). */
char *answer_text(int index);

/* A copy of the numbers `index`, kept for (function, key) until the next such call: a pointer
   the controller may hold as Webots' are held. NULL for no value. */
const double *answer_kept_doubles(int index, const char *function, int key, int *count);
/* Likewise a copy of the text `index`. */
const char *answer_kept_text(int index, const char *function, int key);

/* A call of `function` on a device tag and the integer it answers. */
int call_device_int(const char *function, int tag);
/* A call of `function` on a device tag and the number it answers. */
double call_device_double(const char *function, int tag);
/* A call of `function` with a device tag and one integer, answered by nothing. */
void call_device_set_int(const char *function, int tag, int value);
/* A call of `function` with a device tag and one number, answered by nothing. */
void call_device_set_double(const char *function, int tag, double value);

#endif
