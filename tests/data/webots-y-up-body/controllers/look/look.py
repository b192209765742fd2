"""Prints, row by row, where its camera sees red (R) after one step."""

from controller import Robot

robot = Robot()
camera = robot.getDevice("camera")
camera.enable(32)
robot.step(32)
image = camera.getImage()
width, height = camera.getWidth(), camera.getHeight()


def red(x: int, y: int) -> bool:
    return (
        camera.imageGetRed(image, width, x, y) > 150
        and camera.imageGetBlue(image, width, x, y) < 80
    )


rows = ["".join("R" if red(x, y) else "." for x in range(width)) for y in range(height)]
print("image", "|".join(rows))
