"""The Python twin of c_every_device/c_every_device.c: the same readings, printed alike."""

from controller import Robot

robot = Robot()
step = int(robot.getBasicTimeStep())
camera = robot.getDevice("camera")
accelerometer = robot.getDevice("accelerometer")
gyro = robot.getDevice("gyro")
light = robot.getDevice("ls0")
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
encoder = right.getPositionSensor()
keyboard = robot.getKeyboard()
camera.enable(2 * step)
accelerometer.enable(step)
gyro.enable(step)
light.enable(step)
encoder.enable(step)
keyboard.enable(step)
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(-2.0)
right.setVelocity(3.0)
width, height = camera.getWidth(), camera.getHeight()
print(f"camera {width}x{height}")
n = 0
while robot.step(step) != -1:
    n += 1
    key = keyboard.getKey()
    while key != -1:
        print(f"key {key} at {robot.getTime():.3f}")
        key = keyboard.getKey()
    if n % 8:
        continue
    image = camera.getImage()
    red = image[4 * (4 * width + 3) + 2] if image else -1
    print(f"image {sum(image) if image else 0} red {red}")
    a, g = accelerometer.getValues(), gyro.getValues()
    print(f"a {a[0]:.6f} {a[1]:.6f} {a[2]:.6f} g {g[0]:.6f} {g[1]:.6f} {g[2]:.6f}")
    print(f"light {light.getValue():.6f} encoder {encoder.getValue():.6f}")
