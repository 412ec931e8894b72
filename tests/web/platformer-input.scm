((0 start) (1 right) (40 right a) (41 right) (90 left) (120 left a) (121 left) (150))
