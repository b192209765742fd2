/* Webots' ANSI escape codes for coloured console output (<webots/utils/ansi_codes.h>). */
#ifndef WB_ANSI_CODES_H
#define WB_ANSI_CODES_H

#include <stdio.h>

#define ANSI_RESET "\x1b[0m"
#define ANSI_BOLD "\x1b[1m"
#define ANSI_UNDERLINE "\x1b[4m"
#define ANSI_BLACK_BACKGROUND "\x1b[40m"
#define ANSI_RED_BACKGROUND "\x1b[41m"
#define ANSI_GREEN_BACKGROUND "\x1b[42m"
#define ANSI_YELLOW_BACKGROUND "\x1b[43m"
#define ANSI_BLUE_BACKGROUND "\x1b[44m"
#define ANSI_MAGENTA_BACKGROUND "\x1b[45m"
#define ANSI_CYAN_BACKGROUND "\x1b[46m"
#define ANSI_WHITE_BACKGROUND "\x1b[47m"
#define ANSI_BLACK_FOREGROUND "\x1b[30m"
#define ANSI_RED_FOREGROUND "\x1b[31m"
#define ANSI_GREEN_FOREGROUND "\x1b[32m"
#define ANSI_YELLOW_FOREGROUND "\x1b[33m"
#define ANSI_BLUE_FOREGROUND "\x1b[34m"
#define ANSI_MAGENTA_FOREGROUND "\x1b[35m"
#define ANSI_CYAN_FOREGROUND "\x1b[36m"
#define ANSI_WHITE_FOREGROUND "\x1b[37m"
#define ANSI_CLEAR_SCREEN "\x1b[2J"

/* Clearing Webots' console: an expression (printf's result), as controllers use it. */
#define ANSI_CLEAR_CONSOLE() printf("%s", ANSI_CLEAR_SCREEN)
#define ANSI_CONSOLE_CLEAR ANSI_CLEAR_CONSOLE()

/* printf in a colour, then back to the default style. */
#define ANSI_PRINTF_IN_BLACK(...) \
  (printf("%s", ANSI_BLACK_FOREGROUND), printf(__VA_ARGS__), printf("%s", ANSI_RESET))
#define ANSI_PRINTF_IN_RED(...) \
  (printf("%s", ANSI_RED_FOREGROUND), printf(__VA_ARGS__), printf("%s", ANSI_RESET))
#define ANSI_PRINTF_IN_GREEN(...) \
  (printf("%s", ANSI_GREEN_FOREGROUND), printf(__VA_ARGS__), printf("%s", ANSI_RESET))
#define ANSI_PRINTF_IN_YELLOW(...) \
  (printf("%s", ANSI_YELLOW_FOREGROUND), printf(__VA_ARGS__), printf("%s", ANSI_RESET))
#define ANSI_PRINTF_IN_BLUE(...) \
  (printf("%s", ANSI_BLUE_FOREGROUND), printf(__VA_ARGS__), printf("%s", ANSI_RESET))
#define ANSI_PRINTF_IN_MAGENTA(...) \
  (printf("%s", ANSI_MAGENTA_FOREGROUND), printf(__VA_ARGS__), printf("%s", ANSI_RESET))
#define ANSI_PRINTF_IN_CYAN(...) \
  (printf("%s", ANSI_CYAN_FOREGROUND), printf(__VA_ARGS__), printf("%s", ANSI_RESET))
#define ANSI_PRINTF_IN_WHITE(...) \
  (printf("%s", ANSI_WHITE_FOREGROUND), printf(__VA_ARGS__), printf("%s", ANSI_RESET))

#endif
