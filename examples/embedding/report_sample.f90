! The report's sample run (its driver GYMAIN, every error fixed) from Fortran 2008, through the
! module gyro_api over the C API. Prints the gimbal angles after the last step.
!   gfortran report_sample.f90 -I<dir of gyro_api.mod> -lgyro_fortran -lgyro
program report_sample
  use gyro_api
  implicit none
  type(gyro_report_sample) :: sample
  type(gyro_config) :: config
  type(gyro_model) :: model
  character(len=:), allocatable :: why
  real(c_double) :: pitch(3, 3), yaw(3, 3), turn(3, 3), body(3, 3), gimbal(2), dt
  integer(c_int) :: status
  integer :: steps, i

  if (gyro_report_sample_get(sample, config) /= GYRO_OK) error stop 'no report sample'
  if (model%create(c_double) /= GYRO_OK) error stop 'out of memory'
  status = model%configure(config, why)
  if (status /= GYRO_OK) error stop 'configuration refused: ' // why
  ! The body turns about its own pitch axis, then its yaw axis, every step.
  dt = sample%initg_step_s
  status = gyro_frame_rotation(2, sample%body_rate_rad_s(1) * dt, pitch)
  status = gyro_frame_rotation(3, sample%body_rate_rad_s(2) * dt, yaw)
  turn = matmul(yaw, pitch)
  body = reshape([(merge(1.0_c_double, 0.0_c_double, mod(i, 4) == 0), i = 0, 8)], [3, 3])
  status = model%uncage(body, sample%body_rate_rad_s)
  steps = 0
  do while (status == GYRO_OK .and. steps < sample%steps .and. model%flags() == 0)
    body = matmul(turn, body)  ! the body's attitude at the step's end
    status = model%step_slew(dt, body, sample%slew_rate_rad_s, sample%spin_hz)
    if (status == GYRO_OK) steps = steps + 1
  end do
  if (status /= GYRO_OK) error stop 'step refused: ' // gyro_status_text(status)
  call model%gimbal(gimbal)
  write (*, '(a, i0, a, es19.12, a, es19.12, a)') 'report sample: ', steps, ' steps, gimbal pitch ', gimbal(1), &
    ' yaw ', gimbal(2), ' rad'
  call model%destroy()
end program
