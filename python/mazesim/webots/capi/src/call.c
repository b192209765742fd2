/* Calls a controller waits for (see call.h). */
#include "call.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "link.h"

/* Most values one answer holds. */
#define MAX_VALUES 16

/* Each thread builds its calls and reads its answers in buffers of its own. */
static __thread char *message;
static __thread size_t message_size, message_capacity, count_at;
static __thread int32_t value_count;
/* The function of the call being built, and the size of a value too large for the link that it
   holds (0 for none): such a call is not sent. */
static __thread const char *calling;
static __thread int oversized;

typedef struct {
  int32_t type;
  double number;
  size_t offset; /* into the answer's bytes */
  int32_t size;  /* bytes, or numbers for VALUE_DOUBLES */
} Value;

static __thread Value values[MAX_VALUES];
static __thread int answered;
static __thread char *answer_data;
static __thread size_t answer_capacity;

/* Makes `*buffer` hold at least `needed` bytes, doubling its capacity. */
static void reserve(char **buffer, size_t *capacity, size_t needed) {
  if (needed <= *capacity)
    return;
  size_t wanted = *capacity ? 2 * *capacity : 256;
  while (wanted < needed)
    wanted *= 2;
  *buffer = realloc(*buffer, wanted);
  if (!*buffer)
    link_failed("out of memory");
  *capacity = wanted;
}

static void append(const void *data, size_t size) {
  reserve(&message, &message_capacity, message_size + size);
  memcpy(message + message_size, data, size);
  message_size += size;
}

static void append_int(int32_t value) {
  append(&value, sizeof value);
}

void call_begin(const char *function) {
  calling = function;
  oversized = 0;
  message_size = 0;
  int32_t size = (int32_t)strlen(function);
  append_int(size);
  append(function, (size_t)size);
  count_at = message_size;
  value_count = 0;
  append_int(0);
}

void call_int(int value) {
  append_int(VALUE_INT);
  append_int(value);
  value_count++;
}

void call_double(double value) {
  append_int(VALUE_DOUBLE);
  append(&value, sizeof value);
  value_count++;
}

void call_bytes(const void *data, int size) {
  if (!data || size < 0) {
    append_int(VALUE_NONE);
  } else if (size > LINK_MAX_VALUE_BYTES) {
    oversized = size;
    append_int(VALUE_NONE);
  } else {
    append_int(VALUE_BYTES);
    append_int(size);
    append(data, (size_t)size);
  }
  value_count++;
}

void call_text(const char *text) {
  call_bytes(text, text ? (int)strlen(text) : -1);
}

void call_doubles(const double *numbers, int count) {
  if (!numbers || count < 0) {
    append_int(VALUE_NONE);
  } else if ((size_t)count > LINK_MAX_VALUE_BYTES / sizeof(double)) {
    oversized = count;
    append_int(VALUE_NONE);
  } else {
    append_int(VALUE_DOUBLES);
    append_int(count);
    append(numbers, sizeof(double) * (size_t)count);
  }
  value_count++;
}

static int32_t receive_int(void) {
  int32_t value;
  link_receive(&value, sizeof value);
  return value;
}

int call_end(void) {
  if (oversized) {
    /* Refused as Webots refuses a bad argument: the function answers its default. */
    link_error(calling,
               "(): invalid size=%d argument: more than mazesim carries in a call (%d bytes).",
               oversized, LINK_MAX_VALUE_BYTES);
    answered = 0;
    return 0;
  }
  memcpy(message + count_at, &value_count, sizeof value_count);
  link_start();
  link_lock();
  link_send_with_commands(LINK_CALL, message, message_size);
  int32_t count = receive_int();
  if (count < 0 || count > MAX_VALUES)
    link_failed("mazesim sent a malformed answer");
  size_t used = 0;
  for (int i = 0; i < count; i++) {
    Value *value = &values[i];
    value->type = receive_int();
    value->number = NAN;
    value->size = 0;
    value->offset = used;
    if (value->type == VALUE_INT) {
      value->number = receive_int();
    } else if (value->type == VALUE_DOUBLE) {
      link_receive(&value->number, sizeof value->number);
    } else if (value->type == VALUE_BYTES || value->type == VALUE_DOUBLES) {
      value->size = receive_int();
      size_t unit = value->type == VALUE_BYTES ? 1 : sizeof(double);
      if (value->size < 0 || value->size > (1 << 26))
        link_failed("mazesim sent a malformed answer");
      /* Numbers start at a multiple of 8 bytes; bytes end with a NUL. */
      used = (used + 7) & ~(size_t)7;
      reserve(&answer_data, &answer_capacity, used + unit * (size_t)value->size + 1);
      value->offset = used;
      link_receive(answer_data + used, unit * (size_t)value->size);
      used += unit * (size_t)value->size;
      answer_data[used++] = '\0';
    } else if (value->type != VALUE_NONE) {
      link_failed("mazesim sent a malformed answer");
    }
  }
  answered = count;
  link_unlock();
  return count;
}

int answer_type(int index) {
  return index < answered ? values[index].type : VALUE_NONE;
}

int answer_int(int index) {
  double number = answer_double(index);
  return isnan(number) ? 0 : (int)number;
}

double answer_double(int index) {
  int type = answer_type(index);
  return type == VALUE_INT || type == VALUE_DOUBLE ? values[index].number : NAN;
}

const void *answer_bytes(int index, int *size) {
  if (answer_type(index) != VALUE_BYTES) {
    if (size)
      *size = 0;
    return NULL;
  }
  if (size)
    *size = values[index].size;
  return answer_data + values[index].offset;
}

const double *answer_doubles(int index, int *count) {
  if (answer_type(index) != VALUE_DOUBLES) {
    if (count)
      *count = 0;
    return NULL;
  }
  if (count)
    *count = values[index].size;
  return (const double *)(answer_data + values[index].offset);
}

char *answer_text(int index) {
  int size;
  const char *bytes = answer_bytes(index, &size);
  if (!bytes)
    return NULL;
  char *copy = malloc((size_t)size + 1);
  if (!copy)
    link_failed("out of memory");
  memcpy(copy, bytes, (size_t)size);
  copy[size] = '\0';
  return copy;
}

int call_device_int(const char *function, int tag) {
  call_begin(function);
  call_int(tag);
  call_end();
  return answer_int(0);
}

double call_device_double(const char *function, int tag) {
  call_begin(function);
  call_int(tag);
  call_end();
  return answer_double(0);
}

void call_device_set_int(const char *function, int tag, int value) {
  call_begin(function);
  call_int(tag);
  call_int(value);
  call_end();
}

/* Copies of answers kept for their callers, one per function and key. */
typedef struct Kept {
  const char *function;
  int key;
  void *data;
  struct Kept *next;
} Kept;

static Kept *kept;

/* Makes the copy kept for (function, key) `size` bytes of `data`; returns it. */
static void *keep(const char *function, int key, const void *data, size_t size) {
  link_lock();
  Kept *found = kept;
  while (found && (found->key != key || strcmp(found->function, function) != 0))
    found = found->next;
  if (!found) {
    found = calloc(1, sizeof *found);
    if (!found)
      link_failed("out of memory");
    found->function = function;
    found->key = key;
    found->next = kept;
    kept = found;
  }
  void *copy = realloc(found->data, size ? size : 1);
  if (!copy)
    link_failed("out of memory");
  memcpy(copy, data, size);
  found->data = copy;
  link_unlock();
  return copy;
}

const double *answer_kept_doubles(int index, const char *function, int key, int *count) {
  int size;
  const double *numbers = answer_doubles(index, &size);
  if (count)
    *count = size;
  return numbers ? keep(function, key, numbers, sizeof(double) * (size_t)size) : NULL;
}

const char *answer_kept_text(int index, const char *function, int key) {
  int size;
  const char *bytes = answer_bytes(index, &size);
  /* The answer's bytes end with a NUL. */
  return bytes ? keep(function, key, bytes, (size_t)size + 1) : NULL;
}

void call_device_set_double(const char *function, int tag, double value) {
  call_begin(function);
  call_int(tag);
  call_double(value);
  call_end();
}
