! The module gyro_api against the library: its constants are gyro.h's, a configuration by
! name refuses an unknown field and names a refused one, a float and a double model step in
! their kind, the flags, and the exact step's steady precession (report eq 11).
program gyro_api_test
  use gyro_api
  implicit none
  type(gyro_config) :: config
  type(gyro_report_sample) :: sample
  type(gyro_model) :: model, model32
  type(gyro_rotor_parameters) :: p
  type(gyro_transition) :: tr
  character(len=:), allocatable :: why
  real(c_double) :: eye(3, 3), state(4), g(2), h
  real(c_float) :: eye32(3, 3), g32(2)
  integer :: failures = 0, k

  call expect(gyro_abi_version() == GYRO_ABI_WRITTEN_FOR, 'the ABI')
  call expect(gyro_status_name(GYRO_OK) == 'ok', 'GYRO_OK')
  call expect(gyro_status_name(GYRO_OUT_OF_RANGE) == 'out_of_range', 'GYRO_OUT_OF_RANGE')
  call expect(gyro_status_name(GYRO_OUT_OF_MEMORY) == 'out_of_memory', 'GYRO_OUT_OF_MEMORY')

  call expect(gyro_report_sample_get(sample, config) == GYRO_OK, 'the report sample')
  call expect(config%set('pitch_inertias', 1.0_c_double) /= GYRO_OK, 'an unknown field refused')
  call expect(config%set('friction', -1.0_c_double) == GYRO_OK, 'a field set by name')
  call expect(model%create(c_double) == GYRO_OK, 'a double model')
  call expect(model%configure(config, why) /= GYRO_OK, 'a negative friction refused')
  call expect(index(why, 'friction = -1') == 1, 'the refusal names the field: ' // why)
  call expect(config%set('friction', 5.0_c_double) == GYRO_OK, 'the friction again')
  call expect(config%set('gimbal_cone_limit_rad', 2e-3_c_double) == GYRO_OK, 'a small cone')
  call expect(model%configure(config) == GYRO_OK, 'configured')

  eye = 0
  do k = 1, 3
    eye(k, k) = 1
  end do
  eye32 = real(eye, c_float)
  call expect(model%uncage(eye, sample%body_rate_rad_s) == GYRO_OK, 'uncaged')
  do k = 1, 10
    call expect(model%step_slew(1e-3_c_double, eye, sample%slew_rate_rad_s, sample%spin_hz) == GYRO_OK, 'a step')
  end do
  call model%gimbal(g)
  call expect(iand(model%flags(), GYRO_FLAG_GIMBAL_LIMIT) /= 0 .eqv. acos(cos(g(1)) * cos(g(2))) > 2e-3_c_double, &
              'the gimbal-limit flag where the cone passes the limit')

  call expect(model32%create(c_float) == GYRO_OK, 'a float model')
  call expect(model32%configure(config) == GYRO_OK, 'configured in float')
  call expect(model32%uncage(eye32, real(sample%body_rate_rad_s, c_float)) == GYRO_OK, 'uncaged in float')
  do k = 1, 10
    call expect(model32%step_slew(1e-3_c_float, eye32, real(sample%slew_rate_rad_s, c_float), &
                                  real(sample%spin_hz, c_float)) == GYRO_OK, 'a float step')
  end do
  call model32%gimbal(g32)
  call expect(all(abs(g32 - g) < 1e-6), 'the float model with the double one')
  call model%destroy()
  call model32%destroy()

  ! Under a constant torque the rates settle to eq 11's steady precession.
  h = gyro_angular_momentum(100.0_c_double, 3.0_c_double)
  p = gyro_rotor_parameters(2.25_c_double, 2.0_c_double, 5.0_c_double, h)
  call expect(gyro_make_transition(p, 1e-3_c_double, tr) == GYRO_OK, 'a transition')
  state = 0
  do k = 1, 20000
    if (gyro_advance(tr, [40.0_c_double, -25.0_c_double], state) /= GYRO_OK) failures = failures + 1
  end do
  call expect(abs(state(3) - (5 * 40.0_c_double + h * 25) / (25 + h * h)) < 1e-12_c_double, 'steady theta''')
  call expect(abs(state(4) - (h * 40 - 5 * 25.0_c_double) / (25 + h * h)) < 1e-12_c_double, 'steady psi''')

  if (failures /= 0) error stop 'gyro_api_test: checks failed'
  print '(a)', 'gyro_api: all checks passed'

contains

  subroutine expect(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    if (ok) return
    print '(2a)', 'failed: ', what
    failures = failures + 1
  end subroutine

end program
