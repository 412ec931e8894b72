((0 left a) (30 right a) (80 a) (100 up a) (140))
